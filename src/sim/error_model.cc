// placeholder: filled in by the work on issue 3
#include "foglab/sim/error_model.h"
