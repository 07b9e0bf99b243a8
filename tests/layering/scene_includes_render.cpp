// Compiled as part of the scene layer, this include of a higher layer must
// fail: the scene readers stand below the renderer (CMakeLists.txt, layers).
#include "render/renderer.hpp"
