// libholoray.so's own translation unit: the rest of it is the core, taken whole.
#include "holoray/holoray.hpp"
