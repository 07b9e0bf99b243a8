// The control: the same layer reaches the layers below it and the public
// error types, so the refusals above fail for their include alone.
#include "holoray/errors.hpp"
#include "image/image.hpp"
#include "math/vec.hpp"
#include "scene/scene_desc.hpp"
#include "util/parallel.hpp"
