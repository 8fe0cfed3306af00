// Stream elements and image pixels, for every kernel of a render (the integrators' and the
// accelerators'): the streams hold the image's rows from tileRow on (--tile).
#include "../common/scene_layout.h"
#include "../common/raymath.h"
#include "../common/stream.glsl"

uniform int tileRow;  // the image row of the streams' row 0 (--tile; 0 for the whole image)

// The image pixel (column, row from the top) of this stream element.
uvec2 imagePixel() { return uvec2(gl_FragCoord.xy) + uvec2(0u, uint(tileRow)); }
