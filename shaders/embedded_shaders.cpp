// The arrays themselves are generated next to the .spv files in the build tree.
#include "embedded_shaders.h"
