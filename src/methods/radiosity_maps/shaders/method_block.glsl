// method_block.glsl: the radiosity-maps method's uniform block (layout in methods/radiosity_maps/radiosity_maps_io.h).
#include "methods/radiosity_maps/radiosity_maps_io.h"

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { RadiosityMapsGPU method; };
