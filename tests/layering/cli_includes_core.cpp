// Compiled as a file of the command line, this include of the core's
// internals must fail: the front ends see include/holoray/ and their own
// folders only (CMakeLists.txt, "The front ends").
#include "render/renderer.hpp"
