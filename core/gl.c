/* The core's one copy of the GL entry points (sdk/include/shadelab/gl.h): a module of its own at
 * the bottom, so the renderer, the composer, the app and the harness all call down into it. */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
