#pragma once
// The GL 3.3 core API, and KHR_debug, as glad's generated loader provides it: every gl*
// call goes through a function pointer that GlContext::get() fills in, so
// no GL library is linked and nothing may call GL before GlContext::get().
#include <glad/gl.h>
