#pragma once
// OpenGL 3.3 core entry points. On Linux libGL/libOpenGL (GLVND) export every core function, so
// the prototypes are declared directly instead of loading them through a loader library.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
