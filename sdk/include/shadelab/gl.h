/* OpenGL 4.5 core entry points for the core and for plugins.
 *
 * GL functions are never linked: they come through the active context backend's
 * get-proc-address (libOSMesa does not export everything, and linking libGL and libOSMesa into
 * one process does not work). Each module (the core, every plugin) has its own hidden copy of
 * the pointers and fills it once with sl_gl_load(), e.g. in a plugin's activate():
 *
 *     #define SL_GL_IMPLEMENTATION   // in exactly one .c file of the module
 *     #include <shadelab/gl.h>
 *     ... if (!sl_gl_load(host->gl_get_proc_address, NULL)) return SL_ERR_GL;
 *
 * The list covers what shadelab and its bundled plugins use; a plugin needing another entry
 * point fetches it with gl_get_proc_address itself.
 */
#ifndef SHADELAB_GL_H
#define SHADELAB_GL_H

#include <GL/glcorearb.h> /* types, enums and PFN typedefs only (no prototypes) */
#include <stdbool.h>

#define SL_GL_FUNCTIONS(X) \
    X(PFNGLGETERRORPROC, glGetError) X(PFNGLGETSTRINGPROC, glGetString) \
    X(PFNGLGETSTRINGIPROC, glGetStringi) X(PFNGLGETINTEGERVPROC, glGetIntegerv) \
    X(PFNGLGETFLOATVPROC, glGetFloatv) X(PFNGLENABLEPROC, glEnable) X(PFNGLDISABLEPROC, glDisable) \
    X(PFNGLISENABLEDPROC, glIsEnabled) \
    X(PFNGLVIEWPORTPROC, glViewport) X(PFNGLSCISSORPROC, glScissor) X(PFNGLCLEARPROC, glClear) \
    X(PFNGLCLEARCOLORPROC, glClearColor) X(PFNGLCLEARDEPTHPROC, glClearDepth) \
    X(PFNGLDEPTHFUNCPROC, glDepthFunc) X(PFNGLDEPTHMASKPROC, glDepthMask) \
    X(PFNGLCOLORMASKPROC, glColorMask) X(PFNGLCULLFACEPROC, glCullFace) \
    X(PFNGLFRONTFACEPROC, glFrontFace) X(PFNGLBLENDFUNCPROC, glBlendFunc) \
    X(PFNGLBLENDEQUATIONPROC, glBlendEquation) X(PFNGLPOLYGONOFFSETPROC, glPolygonOffset) \
    X(PFNGLPOLYGONMODEPROC, glPolygonMode) X(PFNGLFINISHPROC, glFinish) X(PFNGLFLUSHPROC, glFlush) \
    X(PFNGLPIXELSTOREIPROC, glPixelStorei) X(PFNGLREADPIXELSPROC, glReadPixels) \
    X(PFNGLREADBUFFERPROC, glReadBuffer) X(PFNGLDRAWBUFFERPROC, glDrawBuffer) \
    X(PFNGLDRAWBUFFERSPROC, glDrawBuffers) \
    X(PFNGLCOLORMASKIPROC, glColorMaski) X(PFNGLDEPTHRANGEPROC, glDepthRange) /* ABI 1.8 */ \
    X(PFNGLTEXTUREVIEWPROC, glTextureView) X(PFNGLCLEARTEXIMAGEPROC, glClearTexImage) /* ABI 1.8 */ \
    /* textures */ \
    X(PFNGLGENTEXTURESPROC, glGenTextures) X(PFNGLDELETETEXTURESPROC, glDeleteTextures) \
    X(PFNGLBINDTEXTUREPROC, glBindTexture) X(PFNGLACTIVETEXTUREPROC, glActiveTexture) \
    X(PFNGLTEXIMAGE2DPROC, glTexImage2D) X(PFNGLTEXIMAGE3DPROC, glTexImage3D) \
    X(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D) X(PFNGLTEXPARAMETERIPROC, glTexParameteri) \
    X(PFNGLTEXPARAMETERFPROC, glTexParameterf) X(PFNGLTEXPARAMETERFVPROC, glTexParameterfv) \
    X(PFNGLGENERATEMIPMAPPROC, glGenerateMipmap) X(PFNGLGETTEXIMAGEPROC, glGetTexImage) \
    X(PFNGLCREATETEXTURESPROC, glCreateTextures) X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D) \
    X(PFNGLTEXTURESTORAGE3DPROC, glTextureStorage3D) \
    X(PFNGLTEXTURESUBIMAGE2DPROC, glTextureSubImage2D) \
    X(PFNGLTEXTURESUBIMAGE3DPROC, glTextureSubImage3D) \
    X(PFNGLTEXTUREPARAMETERIPROC, glTextureParameteri) \
    X(PFNGLTEXTUREPARAMETERFPROC, glTextureParameterf) \
    X(PFNGLTEXTUREPARAMETERFVPROC, glTextureParameterfv) \
    X(PFNGLGENERATETEXTUREMIPMAPPROC, glGenerateTextureMipmap) \
    X(PFNGLBINDTEXTUREUNITPROC, glBindTextureUnit) X(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage) \
    X(PFNGLCOPYIMAGESUBDATAPROC, glCopyImageSubData) \
    X(PFNGLGETTEXTURELEVELPARAMETERIVPROC, glGetTextureLevelParameteriv) \
    X(PFNGLCREATESAMPLERSPROC, glCreateSamplers) X(PFNGLDELETESAMPLERSPROC, glDeleteSamplers) \
    X(PFNGLBINDSAMPLERPROC, glBindSampler) X(PFNGLSAMPLERPARAMETERIPROC, glSamplerParameteri) \
    X(PFNGLSAMPLERPARAMETERFPROC, glSamplerParameterf) \
    X(PFNGLBINDIMAGETEXTUREPROC, glBindImageTexture) \
    /* buffers and vertex arrays */ \
    X(PFNGLGENBUFFERSPROC, glGenBuffers) X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers) \
    X(PFNGLBINDBUFFERPROC, glBindBuffer) X(PFNGLBUFFERDATAPROC, glBufferData) \
    X(PFNGLBUFFERSUBDATAPROC, glBufferSubData) X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase) \
    X(PFNGLBINDBUFFERRANGEPROC, glBindBufferRange) \
    X(PFNGLCREATEBUFFERSPROC, glCreateBuffers) X(PFNGLNAMEDBUFFERDATAPROC, glNamedBufferData) \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage) \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, glNamedBufferSubData) \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, glGetNamedBufferSubData) \
    X(PFNGLMAPNAMEDBUFFERRANGEPROC, glMapNamedBufferRange) \
    X(PFNGLUNMAPNAMEDBUFFERPROC, glUnmapNamedBuffer) \
    X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays) X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays) \
    X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray) X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays) \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, glVertexArrayVertexBuffer) \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, glVertexArrayElementBuffer) \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, glEnableVertexArrayAttrib) \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, glVertexArrayAttribFormat) \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, glVertexArrayAttribBinding) \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray) \
    X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer) \
    X(PFNGLVERTEXATTRIB4FPROC, glVertexAttrib4f) \
    X(PFNGLDRAWARRAYSPROC, glDrawArrays) X(PFNGLDRAWELEMENTSPROC, glDrawElements) \
    X(PFNGLDRAWARRAYSINSTANCEDPROC, glDrawArraysInstanced) \
    X(PFNGLDRAWELEMENTSINSTANCEDPROC, glDrawElementsInstanced) \
    X(PFNGLPATCHPARAMETERIPROC, glPatchParameteri) /* ABI 1.7: DISPLACEMENT patches */ \
    X(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute) X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier) \
    /* framebuffers */ \
    X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers) X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers) \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer) X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers) \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture) \
    X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, glNamedFramebufferTextureLayer) \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, glNamedFramebufferDrawBuffers) \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, glNamedFramebufferDrawBuffer) \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, glNamedFramebufferReadBuffer) \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, glCheckNamedFramebufferStatus) \
    X(PFNGLBLITNAMEDFRAMEBUFFERPROC, glBlitNamedFramebuffer) \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, glClearNamedFramebufferfv) \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFIPROC, glClearNamedFramebufferfi) \
    X(PFNGLCREATERENDERBUFFERSPROC, glCreateRenderbuffers) \
    X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers) \
    X(PFNGLNAMEDRENDERBUFFERSTORAGEPROC, glNamedRenderbufferStorage) \
    X(PFNGLNAMEDFRAMEBUFFERRENDERBUFFERPROC, glNamedFramebufferRenderbuffer) \
    /* shaders and programs */ \
    X(PFNGLCREATESHADERPROC, glCreateShader) X(PFNGLDELETESHADERPROC, glDeleteShader) \
    X(PFNGLSHADERSOURCEPROC, glShaderSource) X(PFNGLCOMPILESHADERPROC, glCompileShader) \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv) X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog) \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram) X(PFNGLDELETEPROGRAMPROC, glDeleteProgram) \
    X(PFNGLATTACHSHADERPROC, glAttachShader) X(PFNGLDETACHSHADERPROC, glDetachShader) \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram) \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv) X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog) \
    X(PFNGLUSEPROGRAMPROC, glUseProgram) X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation) \
    X(PFNGLGETACTIVEUNIFORMPROC, glGetActiveUniform) \
    X(PFNGLGETUNIFORMBLOCKINDEXPROC, glGetUniformBlockIndex) \
    X(PFNGLUNIFORMBLOCKBINDINGPROC, glUniformBlockBinding) \
    X(PFNGLUNIFORM1IPROC, glUniform1i) X(PFNGLUNIFORM1FPROC, glUniform1f) \
    X(PFNGLUNIFORM2FPROC, glUniform2f) X(PFNGLUNIFORM3FPROC, glUniform3f) \
    X(PFNGLUNIFORM4FPROC, glUniform4f) X(PFNGLUNIFORM2IPROC, glUniform2i) \
    X(PFNGLUNIFORM1FVPROC, glUniform1fv) X(PFNGLUNIFORM3FVPROC, glUniform3fv) \
    X(PFNGLUNIFORM4FVPROC, glUniform4fv) X(PFNGLUNIFORM1IVPROC, glUniform1iv) \
    X(PFNGLUNIFORMMATRIX3FVPROC, glUniformMatrix3fv) X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv) \
    X(PFNGLPROGRAMUNIFORM1IPROC, glProgramUniform1i) X(PFNGLPROGRAMUNIFORM1FPROC, glProgramUniform1f) \
    X(PFNGLPROGRAMUNIFORM2FPROC, glProgramUniform2f) X(PFNGLPROGRAMUNIFORM3FPROC, glProgramUniform3f) \
    X(PFNGLPROGRAMUNIFORM4FPROC, glProgramUniform4f) \
    X(PFNGLPROGRAMUNIFORM1FVPROC, glProgramUniform1fv) \
    X(PFNGLPROGRAMUNIFORM4FVPROC, glProgramUniform4fv) \
    X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, glProgramUniformMatrix4fv) \
    /* queries and debug */ \
    X(PFNGLGENQUERIESPROC, glGenQueries) X(PFNGLDELETEQUERIESPROC, glDeleteQueries) \
    X(PFNGLBEGINQUERYPROC, glBeginQuery) X(PFNGLENDQUERYPROC, glEndQuery) \
    X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v) \
    X(PFNGLGETQUERYOBJECTIVPROC, glGetQueryObjectiv) \
    X(PFNGLQUERYCOUNTERPROC, glQueryCounter)

#ifndef SL_GL_VISIBILITY
#define SL_GL_VISIBILITY __attribute__((visibility("hidden")))
#endif

#define SL_GL_DECLARE_(type, name) extern SL_GL_VISIBILITY type sl_##name;
SL_GL_FUNCTIONS(SL_GL_DECLARE_)
#undef SL_GL_DECLARE_

/* Calls in source read as plain GL. */
#include "gl_aliases.h"

typedef void *(*sl_gl_proc_loader)(const char *name);

/* Fills this module's pointers. Returns false (and names the first missing function through
 * *missing when given) if an entry point is absent. */
SL_GL_VISIBILITY bool sl_gl_load(sl_gl_proc_loader load, const char **missing);

#ifdef SL_GL_IMPLEMENTATION
#define SL_GL_DEFINE_(type, name) SL_GL_VISIBILITY type sl_##name;
SL_GL_FUNCTIONS(SL_GL_DEFINE_)
#undef SL_GL_DEFINE_
SL_GL_VISIBILITY bool sl_gl_load(sl_gl_proc_loader load, const char **missing) {
    bool ok = true;
#define SL_GL_LOAD_(type, name) \
    sl_##name = (type)load(#name); \
    if (!sl_##name && ok) { ok = false; if (missing) *missing = #name; }
    SL_GL_FUNCTIONS(SL_GL_LOAD_)
#undef SL_GL_LOAD_
    return ok;
}
#endif

#endif
