// AO may run at the G-buffer's resolution or at half of it. At half resolution, AO pixel p stands for G-buffer pixel
// 2p (the same corner of every 2x2 block), so every pass agrees on one real surface per AO pixel. A rotated-grid
// pick (as the depth hierarchy uses) would make neighbouring AO pixels stand for alternating rows and columns, and
// at every edge the bilateral blur would then keep alternate columns apart: visible stripes.
// CPU mirror: SaoKernel::aoCentrePixel.
uniform vec2 u_gbufferSize;  // G-buffer size in pixels
uniform float u_aoScale;     // 1 (full resolution) or 2 (half resolution)

vec2 gbufferPixelOf(vec2 aoPixel) { return min(aoPixel * u_aoScale, u_gbufferSize - 1.0); }
