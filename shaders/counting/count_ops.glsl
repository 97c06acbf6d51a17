// The counting build's prelude (shaders/CMakeLists.txt inserts it after a shader's #version and
// #extension lines and compiles the shader a second time as NAME@count). Every texture and image
// access of the shader also adds one to its kind's 64-bit counter in the dispatch's own slot of a
// storage buffer (replay/vk/op_counter.h), so a replay counts what each pass really executed.
// Function-like macros do not expand inside their own expansion, so the wrapped call is the
// builtin. The binding is outside the shader's own dense bindings; reflection sets it apart by
// its block name, AoOpCounts.
// Counter order: kAoOpFetch texelFetch, kAoOpSample textureLod, kAoOpGather textureGather[Offset],
// kAoOpImageLoad imageLoad, kAoOpImageStore imageStore (op_counter.h's OpKind, same order).
layout(set = 0, binding = 31, std430) buffer AoOpCounts { uint aoOpCounts[]; };

// Low word, and the high word on its carry: a 4K frame exceeds 2^32 fetches in some passes.
void aoCountOp(uint kind) {
  uint old = atomicAdd(aoOpCounts[2u * kind], 1u);
  if (old == 0xffffffffu) atomicAdd(aoOpCounts[2u * kind + 1u], 1u);
}

#define texelFetch(s, p, l) (aoCountOp(0u), texelFetch(s, p, l))
#define textureLod(s, p, l) (aoCountOp(1u), textureLod(s, p, l))
#define textureGather(s, p) (aoCountOp(2u), textureGather(s, p))
#define textureGatherOffset(s, p, o) (aoCountOp(2u), textureGatherOffset(s, p, o))
#define imageLoad(i, p) (aoCountOp(3u), imageLoad(i, p))
#define imageStore(i, p, v) (aoCountOp(4u), imageStore(i, p, v))
