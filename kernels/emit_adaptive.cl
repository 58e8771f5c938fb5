/* emit_adaptive.cl — wavefront stage 1 with the `adaptive` strategy (lib/emit_adaptive.h) in the one
 * emission wrapper (lib/emit_kernel.h). Build with -DFEN_BVH_WIDTH (portal sets have the scene's layout).
 */
#include "lib/emit_adaptive.h"

#define FEN_EMITTER_TYPE AdaptiveEmitter
#define FEN_EMITTER_ARGS FEN_ADAPTIVE_ARGS
#define FEN_EMITTER_MAKE FEN_ADAPTIVE_EMITTER
#define FEN_EMITTER_EMIT emit_adaptive
#define FEN_EMITTER_REJECTS 1
#define FEN_EMITTER_OPENINGS 1 /* lib/opening_walk.h */

#include "lib/emit_kernel.h"
