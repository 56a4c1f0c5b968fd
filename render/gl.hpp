#pragma once
// The GL headers as OSMesa provides them: core-profile entry points are
// exported by libOSMesa itself (GL_GLEXT_PROTOTYPES is set by CMake).
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>
