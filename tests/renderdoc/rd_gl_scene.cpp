// rd_gl_scene: rd_scene's known scene (scene.h) drawn through OpenGL 3.3 core profile (Xlib + GLX,
// functions through libepoxy), for the RenderDoc import's OpenGL side. It renders into a
// framebuffer object, captures each frame through RenderDoc's in-application API and writes its
// own read-back beside the captures:
//   CAPTURE_DIR/NNNN.rdc        RenderDoc capture of frame N
//   READBACK_DIR/NNNN.depth     glReadPixels(GL_DEPTH_COMPONENT, GL_FLOAT): width*height floats,
//                               little-endian, GL's row order (row 0 is window y 0, the bottom)
//   READBACK_DIR/NNNN.normals   the RGBA16F normal target's bits (width*height*4 halves), same order
//   READBACK_DIR/NNNN.json      width, height, depth format, clip_control, reversed, view and
//                               projection (column-major, exactly what was uploaded)
// Usage: rd_gl_scene --depth-format d16|d24|d24s8|d32f|d32fs8 [--clip-control] [--reversed] [--last-draw-points] [--final-copy]
//                    [--camera ubo|globals|combined] [--default-framebuffer | --post-process] [--depth-range N,F]
//                    [--size WxH] [--frames N] [--capture-dir DIR] --readback-dir DIR
// Projection: by default GL's own conventions (clip z in [-1, 1], y up, glm::perspectiveRH_NO);
// --clip-control calls glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE) and uploads scene.h's
// [0, 1], y-down projection, so the picture stays upright; --reversed (only with --clip-control)
// reverses depth (clear 0, GL_GREATER). A stencil aspect is cleared to 0xA5 and left alone.
// --camera: where the vertex shader finds the camera (shaders/gl_scene.vert): a uniform block
// (default), default-block uniforms view and projection, or one default-block view_projection.
// --default-framebuffer draws the scene into the window's own framebuffer (D24S8, the only depth
// a GLX visual offers here) instead of the FBO; --post-process follows the scene with a pass that
// samples the FBO's normal target into the window, as an engine's tone mapping does.
// --depth-range calls glDepthRange(N, F) for the scene (default 0, 1); N > F reverses depth
// (clear 0, GL_GREATER) as --reversed does.
//
// RenderDoc hooks OpenGL by interposing the GLX entry points and dlopen, so librenderdoc.so must
// be in the process before libepoxy opens libGL: with --capture-dir the program re-executes
// itself with librenderdoc.so in LD_PRELOAD (unless RenderDoc is already there, e.g. when run
// under renderdoccmd), then uses the in-application API's StartFrameCapture/EndFrameCapture.
// The whole program needs an X display; headless, run it under `xvfb-run -a`.
#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <renderdoc_app.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "scene.h"
#include "test_program_support.h"

// Last: Xlib.h (through epoxy/glx.h) defines macros such as None, Bool and Status.
#include <epoxy/gl.h>
#include <epoxy/glx.h>

namespace fs = std::filesystem;
using namespace aor::rdtest;

namespace {

// The GLSL sources (shaders/gl_scene.vert, .frag), embedded by CMake.
#include "gl_scene_shaders.inc"

struct DepthFormat {
  GLenum internalFormat, format, type;
  bool stencil;
};

const std::map<std::string, DepthFormat>& depthFormats() {
  static const std::map<std::string, DepthFormat> formats = {
      {"d16", {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, false}},
      {"d24", {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, false}},
      {"d24s8", {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, true}},
      {"d32f", {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, false}},
      {"d32fs8", {GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, true}}};
  return formats;
}

struct Options {
  std::string depthFormatName;
  bool clipControl = false, reversed = false;
  bool lastDrawPoints = false;  // the last box drawn as points: a draw the self-check cannot follow
  bool finalCopy = false;       // a full-screen draw after the scene, depth test and writes off
  std::string camera = "ubo";
  bool defaultFramebuffer = false, postProcess = false;
  double depthNear = 0.0, depthFar = 1.0;
  int width = 160, height = 90, frames = 1;
  fs::path captureDir, readbackDir;
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr, "rd_gl_scene: %s\n", problem.c_str());
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--depth-format") {
      o.depthFormatName = value();
      if (!depthFormats().count(o.depthFormatName)) usage("unknown depth format " + o.depthFormatName);
    } else if (a == "--clip-control") {
      o.clipControl = true;
    } else if (a == "--last-draw-points") {
      o.lastDrawPoints = true;
    } else if (a == "--final-copy") {
      o.finalCopy = true;
    } else if (a == "--camera") {
      o.camera = value();
      if (o.camera != "ubo" && o.camera != "globals" && o.camera != "combined") usage("unknown --camera " + o.camera);
    } else if (a == "--default-framebuffer") {
      o.defaultFramebuffer = true;
    } else if (a == "--depth-range") {
      if (std::sscanf(value().c_str(), "%lf,%lf", &o.depthNear, &o.depthFar) != 2) usage("--depth-range is N,F");
    } else if (a == "--post-process") {
      o.postProcess = true;
    } else if (a == "--reversed") {
      o.reversed = true;
    } else if (a == "--size") {
      if (std::sscanf(value().c_str(), "%dx%d", &o.width, &o.height) != 2) usage("--size is WxH");
    } else if (a == "--frames") {
      o.frames = std::atoi(value().c_str());
    } else if (a == "--capture-dir") {
      o.captureDir = value();
    } else if (a == "--readback-dir") {
      o.readbackDir = value();
    } else {
      usage("unknown argument " + a);
    }
  }
  if (o.depthFormatName.empty()) usage("--depth-format is required");
  if (o.readbackDir.empty()) usage("--readback-dir is required");
  if (o.frames < 1 || o.width < 1 || o.height < 1) usage("bad --frames or --size");
  if (o.reversed && !o.clipControl) usage("--reversed needs --clip-control (depth in [0, 1])");
  if (o.defaultFramebuffer && o.depthFormatName != "d24s8") usage("--default-framebuffer is d24s8");
  if (o.defaultFramebuffer && o.postProcess) usage("--post-process reads the FBO: not with --default-framebuffer");
  return o;
}

// Makes sure librenderdoc.so is loaded ahead of every GL library: if it is not in the process yet,
// re-execute this program with it in LD_PRELOAD. Returns the in-application API.
constexpr const char* kPreloadMarker = "RD_GL_SCENE_RENDERDOC_PRELOADED";

RENDERDOC_API_1_6_0* preloadRenderDoc(char** argv) {
  auto getApi = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(RTLD_DEFAULT, "RENDERDOC_GetAPI"));
  if (!getApi) {
    if (std::getenv(kPreloadMarker)) usage("librenderdoc.so in LD_PRELOAD did not load (Debian: librenderdoc)");
    std::string preload = "librenderdoc.so";
    if (const char* old = std::getenv("LD_PRELOAD"); old && *old) preload += std::string(":") + old;
    setenv("LD_PRELOAD", preload.c_str(), 1);
    setenv(kPreloadMarker, "1", 1);
    execv("/proc/self/exe", argv);
    usage(std::string("cannot re-execute with librenderdoc.so preloaded: ") + std::strerror(errno));
  }
  unsetenv(kPreloadMarker);  // nothing this program starts should inherit the hook
  RENDERDOC_API_1_6_0* api = nullptr;
  if (!getApi(eRENDERDOC_API_Version_1_6_0, reinterpret_cast<void**>(&api)) || !api)
    usage("librenderdoc.so has no usable RENDERDOC_GetAPI 1.6.0");
  return api;
}

// A GL 3.3 core profile context on an X window of the frame's size, mapped (its own framebuffer
// has D24S8 depth for --default-framebuffer).
struct GlContext {
  Display* display = nullptr;
  Window window = 0;
  Colormap colormap = 0;
  GLXContext context = nullptr;

  explicit GlContext(const Options& o) {
    display = XOpenDisplay(nullptr);
    if (!display) throw std::runtime_error("cannot open the X display (headless: run under xvfb-run -a)");
    const int screen = DefaultScreen(display);
    if (!epoxy_has_glx_extension(display, screen, "GLX_ARB_create_context_profile"))
      throw std::runtime_error("GLX_ARB_create_context_profile is missing");
    const int fbAttributes[] = {GLX_X_RENDERABLE, True, GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT, GLX_RENDER_TYPE,
                                GLX_RGBA_BIT, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8,
                                GLX_DOUBLEBUFFER, True, GLX_DEPTH_SIZE, 24, GLX_STENCIL_SIZE, 8, 0};
    int count = 0;
    GLXFBConfig* configs = glXChooseFBConfig(display, screen, fbAttributes, &count);
    if (!configs || count == 0) throw std::runtime_error("no suitable GLXFBConfig");
    const GLXFBConfig config = configs[0];
    XFree(configs);
    XVisualInfo* visual = glXGetVisualFromFBConfig(display, config);
    if (!visual) throw std::runtime_error("no X visual for the GLXFBConfig");
    XSetWindowAttributes attributes{};
    colormap = XCreateColormap(display, RootWindow(display, screen), visual->visual, AllocNone);
    attributes.colormap = colormap;
    attributes.event_mask = StructureNotifyMask;
    window = XCreateWindow(display, RootWindow(display, screen), 0, 0, unsigned(o.width), unsigned(o.height), 0,
                           visual->depth, InputOutput, visual->visual, CWColormap | CWEventMask, &attributes);
    XFree(visual);
    XMapWindow(display, window);
    XEvent event;
    do XNextEvent(display, &event);
    while (event.type != MapNotify);
    const int contextAttributes[] = {GLX_CONTEXT_MAJOR_VERSION_ARB, 3, GLX_CONTEXT_MINOR_VERSION_ARB, 3,
                                     GLX_CONTEXT_PROFILE_MASK_ARB, GLX_CONTEXT_CORE_PROFILE_BIT_ARB, 0};
    context = glXCreateContextAttribsARB(display, config, nullptr, True, contextAttributes);
    if (!context) throw std::runtime_error("glXCreateContextAttribsARB (3.3 core) failed");
    if (!glXMakeCurrent(display, window, context)) throw std::runtime_error("glXMakeCurrent failed");
  }
  ~GlContext() {
    if (context) {
      glXMakeCurrent(display, 0, nullptr);
      glXDestroyContext(display, context);
    }
    if (window) XDestroyWindow(display, window);
    if (colormap) XFreeColormap(display, colormap);
    if (display) XCloseDisplay(display);
  }
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;
};

void checkGl(const char* where) {
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    char text[96];
    std::snprintf(text, sizeof text, "GL error 0x%04x %s", e, where);
    throw std::runtime_error(text);
  }
}

// Shaders and programs report their status and log through functions of the same shapes.
using GetStatus = void (*)(GLuint, GLenum, GLint*);
using GetLog = void (*)(GLuint, GLsizei, GLsizei*, GLchar*);
void checkStatus(GLuint object, GLenum status, GetStatus getStatus, GetLog getLog, const char* what) {
  GLint ok = 0;
  getStatus(object, status, &ok);
  if (ok) return;
  char log[2048];
  getLog(object, sizeof log, nullptr, log);
  throw std::runtime_error(std::string(what) + ": " + log);
}

GLuint compile(GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  checkStatus(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, "shader compile");
  return shader;
}

constexpr GLint kClearStencil = 0xA5;

// The vertex shader with `define` (one line, may be empty) put after its #version line.
GLuint link(const std::string& vertex, const char* fragment, const std::string& define = "") {
  std::string source = vertex;
  source.insert(source.find('\n') + 1, define);
  const GLuint vs = compile(GL_VERTEX_SHADER, source.c_str()), frag = compile(GL_FRAGMENT_SHADER, fragment);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, frag);
  glLinkProgram(program);
  checkStatus(program, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, "program link");
  glDeleteShader(vs);
  glDeleteShader(frag);
  return program;
}

// --final-copy: a full-screen triangle after the scene, depth test and writes off with the
// depth target still bound, as an engine's final composite is.
constexpr const char* kCopyVert = R"glsl(#version 330 core
void main() { gl_Position = vec4(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1), 0.0, 1.0); }
)glsl";
constexpr const char* kCopyFrag = R"glsl(#version 330 core
out vec4 colour;
void main() { colour = vec4(0.0, 0.0, 1.0, 1.0); }
)glsl";

// --post-process: the FBO's normals (texture unit 0) to the window, remapped to [0, 1].
constexpr const char* kPostFrag = R"glsl(#version 330 core
uniform sampler2D sceneNormals;
out vec4 colour;
void main() { colour = vec4(texelFetch(sceneNormals, ivec2(gl_FragCoord.xy), 0).xyz * 0.5 + 0.5, 1.0); }
)glsl";

GLint uniformLocation(GLuint program, const char* name) {
  const GLint location = glGetUniformLocation(program, name);
  if (location < 0) throw std::runtime_error(std::string("no uniform ") + name);
  return location;
}

struct SceneGl {
  GLuint program = 0, copyProgram = 0, postProgram = 0, vao = 0, vertexBuffer = 0, uniformBuffer = 0;
  GLuint framebuffer = 0, normalTexture = 0, depthTexture = 0;
  GLint modelLocation = -1, viewLocation = -1, projectionLocation = -1, viewProjectionLocation = -1;
  std::vector<uint32_t> firstVertex;

  void findCamera(const Options& o) {
    if (o.camera == "globals") {
      viewLocation = uniformLocation(program, "view");
      projectionLocation = uniformLocation(program, "projection");
    } else if (o.camera == "combined") {
      viewProjectionLocation = uniformLocation(program, "view_projection");
    } else {
      const GLuint block = glGetUniformBlockIndex(program, "SceneData");
      if (block == GL_INVALID_INDEX) throw std::runtime_error("no uniform block SceneData");
      glUniformBlockBinding(program, block, 0);
    }
    modelLocation = uniformLocation(program, "model");
  }

  SceneGl(const Options& o) {
    const std::string define = o.camera == "globals" ? "#define CAMERA_GLOBALS\n"
                               : o.camera == "combined" ? "#define CAMERA_COMBINED\n" : "";
    program = link(kGlSceneVert, kGlSceneFrag, define);
    if (o.finalCopy) copyProgram = link(kCopyVert, kCopyFrag);
    if (o.postProcess) postProgram = link(kCopyVert, kPostFrag);
    findCamera(o);

    const SceneMesh mesh = sceneMesh();
    firstVertex = mesh.firstVertex;
    static_assert(sizeof(Vertex) == 24);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vertexBuffer);
    glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof(Vertex)), mesh.vertices.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, normal)));
    glBindVertexArray(0);

    glGenBuffers(1, &uniformBuffer);
    glBindBuffer(GL_UNIFORM_BUFFER, uniformBuffer);
    glBufferData(GL_UNIFORM_BUFFER, 3 * sizeof(glm::mat4), nullptr, GL_DYNAMIC_DRAW);

    const DepthFormat& d = depthFormats().at(o.depthFormatName);
    auto texture = [&](GLenum internalFormat, GLenum format, GLenum type) {
      GLuint t = 0;
      glGenTextures(1, &t);
      glBindTexture(GL_TEXTURE_2D, t);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
      glTexImage2D(GL_TEXTURE_2D, 0, GLint(internalFormat), o.width, o.height, 0, format, type, nullptr);
      return t;
    };
    normalTexture = texture(GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT);
    depthTexture = texture(d.internalFormat, d.format, d.type);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, normalTexture, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, d.stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                           GL_TEXTURE_2D, depthTexture, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("the framebuffer is incomplete for " + o.depthFormatName);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("creating the scene's objects");
  }

  // One frame: clear, a draw per object (floor, then each box), glFinish.
  void render(const Options& o, const Camera& camera) {
    const DepthFormat& d = depthFormats().at(o.depthFormatName);
    if (o.clipControl) glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glBindBuffer(GL_UNIFORM_BUFFER, uniformBuffer);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof(glm::mat4), glm::value_ptr(camera.view));
    glBufferSubData(GL_UNIFORM_BUFFER, sizeof(glm::mat4), sizeof(glm::mat4), glm::value_ptr(camera.projection));
    const glm::mat4 light = glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, 0.5f, 20.0f);
    glBufferSubData(GL_UNIFORM_BUFFER, 2 * sizeof(glm::mat4), sizeof(glm::mat4), glm::value_ptr(light));
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, uniformBuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, o.defaultFramebuffer ? 0 : framebuffer);
    const GLenum drawBuffer = o.defaultFramebuffer ? GL_BACK : GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &drawBuffer);
    glViewport(0, 0, o.width, o.height);
    glDepthRange(o.depthNear, o.depthFar);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    const bool nearIsGreater = o.reversed || o.depthNear > o.depthFar;  // reversed by clip control or by range
    glDepthFunc(nearIsGreater ? GL_GREATER : GL_LESS);
    glDisable(GL_CULL_FACE);
    const GLfloat clearNormal[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, clearNormal);
    const GLfloat clearDepth = nearIsGreater ? 0.0f : 1.0f;
    if (d.stencil)  // a stencil value whose bits cannot pass for depth's (nothing tests stencil)
      glClearBufferfi(GL_DEPTH_STENCIL, 0, clearDepth, kClearStencil);
    else
      glClearBufferfv(GL_DEPTH, 0, &clearDepth);
    glUseProgram(program);
    uploadCamera(camera);
    glBindVertexArray(vao);
    const glm::mat4 model(1.0f);
    for (size_t object = 0; object + 1 < firstVertex.size(); ++object) {
      glUniformMatrix4fv(modelLocation, 1, GL_FALSE, glm::value_ptr(model));
      const bool points = o.lastDrawPoints && object + 2 == firstVertex.size();
      glDrawArrays(points ? GL_POINTS : GL_TRIANGLES, GLint(firstVertex[object]), GLsizei(firstVertex[object + 1] - firstVertex[object]));
    }
    if (copyProgram) {
      glDisable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glUseProgram(copyProgram);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    if (postProgram) postProcess();
    glBindVertexArray(0);
    glFinish();
    checkGl("rendering the frame");
  }

  // The default-block camera of --camera globals and combined (the uniform block is filled anyway).
  void uploadCamera(const Camera& camera) {
    if (viewLocation >= 0) glUniformMatrix4fv(viewLocation, 1, GL_FALSE, glm::value_ptr(camera.view));
    if (projectionLocation >= 0) glUniformMatrix4fv(projectionLocation, 1, GL_FALSE, glm::value_ptr(camera.projection));
    if (viewProjectionLocation >= 0)
      glUniformMatrix4fv(viewProjectionLocation, 1, GL_FALSE, glm::value_ptr(camera.projection * camera.view));
  }

  // The window's framebuffer gets the FBO's normals: a full-screen triangle, no depth test.
  void postProcess() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDrawBuffer(GL_BACK);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, normalTexture);
    glUseProgram(postProgram);
    glUniform1i(uniformLocation(postProgram, "sceneNormals"), 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTexture(GL_TEXTURE_2D, 0);
  }

  // GL's row order: row 0 is window y 0 (the bottom).
  void readBack(const Options& o, std::vector<float>& depth, std::vector<uint16_t>& normalsHalf) {
    depth.assign(size_t(o.width) * size_t(o.height), 0.0f);
    normalsHalf.assign(size_t(o.width) * size_t(o.height) * 4, 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, o.defaultFramebuffer ? 0 : framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, o.width, o.height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    glReadBuffer(o.defaultFramebuffer ? GL_BACK : GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, o.width, o.height, GL_RGBA, GL_HALF_FLOAT, normalsHalf.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    checkGl("reading the frame back");
  }
};

// GL's conventions by default; with glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE) scene.h's own
// [0, 1], y-down projection (the y flip of GL_UPPER_LEFT undoes its y-down, so it stays upright).
Camera glCamera(const Options& o, int frame) {
  Camera c = sceneCamera(frame, o.width, o.height, o.reversed);
  if (!o.clipControl)
    c.projection = glm::perspectiveRH_NO(glm::radians(kVerticalFovDegrees), float(o.width) / float(o.height),
                                         kNear, kFar);
  return c;
}


}  // namespace

int main(int argc, char** argv) {
  const Options o = parseOptions(argc, argv);
  RENDERDOC_API_1_6_0* api = nullptr;
  if (!o.captureDir.empty()) api = preloadRenderDoc(argv);  // may re-execute; before any GL call
  try {
    fs::create_directories(o.readbackDir);
    if (api) {
      fs::create_directories(o.captureDir);
      api->SetCaptureFilePathTemplate((o.captureDir / "rd_gl_scene").c_str());
    }
    GlContext gl(o);
    SceneGl scene(o);
    for (int frame = 0; frame < o.frames; ++frame) {
      const Camera camera = glCamera(o, frame);
      void* device = gl.context;  // RenderDoc's device pointer for GL is the context handle
      if (api) api->StartFrameCapture(device, nullptr);
      scene.render(o, camera);
      char stem[16];
      std::snprintf(stem, sizeof stem, "%04d", frame);
      if (api) {
        if (!api->EndFrameCapture(device, nullptr)) usage("RenderDoc did not end the frame capture");
        moveNewestCapture(api, o.captureDir / (std::string(stem) + ".rdc"));
      }
      std::vector<float> depth;
      std::vector<uint16_t> normalsHalf;
      scene.readBack(o, depth, normalsHalf);
      glXSwapBuffers(gl.display, gl.window);
      writeBinary(o.readbackDir / (std::string(stem) + ".depth"), depth);
      writeBinary(o.readbackDir / (std::string(stem) + ".normals"), normalsHalf);
      nlohmann::json meta = {{"width", o.width},
                             {"height", o.height},
                             {"depth_format", o.depthFormatName},
                             {"clip_control", o.clipControl},
                             {"reversed", o.reversed},
                             {"camera", o.camera},
                             {"default_framebuffer", o.defaultFramebuffer},
                             {"post_process", o.postProcess},
                             {"depth_range", {o.depthNear, o.depthFar}},
                             {"view", matrixJson(camera.view)},
                             {"projection", matrixJson(camera.projection)}};
      std::ofstream(o.readbackDir / (std::string(stem) + ".json")) << meta.dump(2) << "\n";
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rd_gl_scene: %s\n", e.what());
    return 1;
  }
  return 0;
}
