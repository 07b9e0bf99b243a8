// Compiled as part of the scene layer, the public API's renderer header must
// not be found: of include/holoray/, only the error types stand at the ground.
#include "holoray/render.hpp"
