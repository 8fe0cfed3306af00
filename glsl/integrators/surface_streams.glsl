// The streams a bounce pass reads (whitted/bounce.frag, path/bounce.frag): the surface records the
// surface pass wrote, the light gathered at them, and the paths' state so far.
uniform sampler2D surfacePoint;    // (p, triangle | -1)
uniform sampler2D surfaceNormal;   // (facing geometric normal, material)
uniform sampler2D surfaceView;     // (ray direction, barycentric u)
uniform sampler2D surfaceShading;  // (shading normal, barycentric v)
uniform sampler2D localColor;      // the light gathered at the hit
uniform sampler2D colorState;      // the path's colour so far
uniform sampler2D weightState;     // (throughput, alive)
uniform sampler2D pathStateIn;     // Whitted: (depth, stack height, rays after the first, 0); path: (pdf of the ray's direction, pixel x, pixel y, features closed)
