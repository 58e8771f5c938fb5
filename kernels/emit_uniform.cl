/* emit_uniform.cl — wavefront stage 1 with the `uniform` strategy (lib/emit_uniform.h) in the one
 * emission wrapper (lib/emit_kernel.h).
 */
#include "lib/emit_uniform.h"

#define FEN_EMITTER_TYPE UniformEmitter
#define FEN_EMITTER_ARGS FEN_UNIFORM_ARGS
#define FEN_EMITTER_MAKE FEN_UNIFORM_EMITTER
#define FEN_EMITTER_EMIT emit_uniform
#define FEN_EMITTER_REJECTS 0

#include "lib/emit_kernel.h"
