/* emit_portal.cl — wavefront stage 1 with the `portal` strategy (lib/emit_portal.h) in the one
 * emission wrapper (lib/emit_kernel.h). Build with -DFEN_BVH_WIDTH (the portals' BVH has the scene's layout).
 */
#include "lib/emit_portal.h"

#define FEN_EMITTER_TYPE PortalEmitter
#define FEN_EMITTER_ARGS FEN_PORTAL_ARGS
#define FEN_EMITTER_MAKE FEN_PORTAL_EMITTER
#define FEN_EMITTER_EMIT emit_portal
#define FEN_EMITTER_REJECTS 1

#include "lib/emit_kernel.h"
