// D3D11 triangle-domain patterns of Microsoft's reference tessellator, which Mesa's draw module
// runs for OpenGL tessellation on llvmpipe: a patch of three vertices through a tessellation
// control shader that sets the factors and an evaluation shader whose gl_TessCoord is captured
// by transform feedback, triangle by triangle in the order the tessellator emits them.
// Built and run by generate.py (needs libegl-dev, libgl-dev, libgl1-mesa-dri).
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static GLuint shader(GLenum type, const char* src) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, NULL);
  glCompileShader(s);
  GLint ok; glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) { char log[2000]; glGetShaderInfoLog(s, 2000, NULL, log); fprintf(stderr, "shader: %s\n", log); exit(1); }
  return s;
}

int main(int argc, char** argv) {
  // argv[1]: equal_spacing|fractional_odd_spacing|fractional_even_spacing, argv[2]: ccw|cw.
  // stdin: lines "e0 e1 e2 inner" (float bits, hex). stdout: per line the factors, the number of
  // triangles and their corners' (u, v) in 16.16 (exact: the tessellator's points are 16.16).
  PFNEGLGETPLATFORMDISPLAYEXTPROC getdisp = (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  EGLDisplay dpy = getdisp(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  if (!eglInitialize(dpy, NULL, NULL)) { fprintf(stderr, "eglInitialize\n"); return 1; }
  eglBindAPI(EGL_OPENGL_API);
  EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig cfg; EGLint n = 0;
  eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n);
  EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, n ? cfg : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attr);
  if (!ctx || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) { fprintf(stderr, "context\n"); return 1; }

  const char* vs = "#version 450\nvoid main() { gl_Position = vec4(0); }\n";
  const char* tcs = "#version 450\nlayout(vertices = 3) out; uniform vec4 f;\n"
                    "void main() { gl_TessLevelOuter[0] = f.x; gl_TessLevelOuter[1] = f.y; gl_TessLevelOuter[2] = f.z;"
                    " gl_TessLevelInner[0] = f.w; gl_out[gl_InvocationID].gl_Position = vec4(0); }\n";
  char tes[512];
  snprintf(tes, sizeof tes, "#version 450\nlayout(triangles, %s, %s) in; out vec3 tc;\n"
           "void main() { tc = gl_TessCoord; gl_Position = vec4(0); }\n", argv[1], argv[2]);
  GLuint prog = glCreateProgram();
  glAttachShader(prog, shader(GL_VERTEX_SHADER, vs));
  glAttachShader(prog, shader(GL_TESS_CONTROL_SHADER, tcs));
  glAttachShader(prog, shader(GL_TESS_EVALUATION_SHADER, tes));
  const char* varyings[] = {"tc"};
  glTransformFeedbackVaryings(prog, 1, varyings, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(prog);
  GLint ok; glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) { char log[2000]; glGetProgramInfoLog(prog, 2000, NULL, log); fprintf(stderr, "link: %s\n", log); return 1; }
  glUseProgram(prog);
  GLuint vao; glGenVertexArrays(1, &vao); glBindVertexArray(vao);
  glPatchParameteri(GL_PATCH_VERTICES, 3);
  const size_t cap = 64 * 64 * 2 * 3 * 3 * 4 * 2;
  GLuint buf; glGenBuffers(1, &buf);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buf);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, cap, NULL, GL_DYNAMIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buf);
  GLuint q; glGenQueries(1, &q);
  // No default framebuffer without a surface: draws need one, even with rasterization off.
  GLuint fbo, rb; glGenFramebuffers(1, &fbo); glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, &rb); glBindRenderbuffer(GL_RENDERBUFFER, rb); glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  glEnable(GL_RASTERIZER_DISCARD);
  GLint loc = glGetUniformLocation(prog, "f");
  unsigned bits[4];
  while (scanf("%x %x %x %x", &bits[0], &bits[1], &bits[2], &bits[3]) == 4) {
    float f[4]; memcpy(f, bits, sizeof f);
    glUniform4f(loc, f[0], f[1], f[2], f[3]);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, q);
    glBeginTransformFeedback(GL_TRIANGLES);
    glDrawArrays(GL_PATCHES, 0, 3);
    glEndTransformFeedback();
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    GLuint prims = 0; glGetQueryObjectuiv(q, GL_QUERY_RESULT, &prims);
    const float* d = (const float*)glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, (size_t)prims * 9 * 4, GL_MAP_READ_BIT);
    printf("%08x %08x %08x %08x %u", bits[0], bits[1], bits[2], bits[3], prims);
    for (GLuint i = 0; i < prims * 3; ++i) printf(" %x,%x", (unsigned)(d[3 * i] * 65536.0f), (unsigned)(d[3 * i + 1] * 65536.0f));
    printf("\n");
    glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
  }
  return 0;
}
