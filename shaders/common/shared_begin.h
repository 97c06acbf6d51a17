// Lets one header compile as GLSL and as C++ (with GLM), so pass constants, defaults and core math
// have a single definition used by the shaders and by the CPU mirror in replay/cpu/.
// Include shared_end.h at the end of every header that includes this one.
#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace aor::shader {
using namespace glm;
using uint = uint32_t;
#define AOR_OUT(T) T&
#define AOR_INOUT(T) T&
#define AOR_CONST constexpr
#define AOR_FUNC inline
#define AOR_UNROLL
#else
#define AOR_OUT(T) out T
#define AOR_INOUT(T) inout T
#define AOR_CONST const
#define AOR_FUNC
// Asks for a loop to be unrolled fully. lavapipe's NIR leaves loops with large bodies rolled,
// and rolled loops are slow there (gtao_pixel.glsl says how much). Needs
// GL_EXT_control_flow_attributes in the including shader.
#define AOR_UNROLL [[unroll]]
#endif
