// The control: a file of the command line reaches the public API, its own
// folder and MPI's front-end folder, so the refusal above fails for its
// include alone.
#include "cli/option_parsing.hpp"
#include "cluster/row_bands.hpp"
#include "holoray/holoray.hpp"
