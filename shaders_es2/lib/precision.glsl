// Fragment precision. The 16-bit depth packing needs highp (mediump floats hold only 11 significant bits); the
// renderer checks GL_HIGH_FLOAT support before building any program and refuses the context without it.
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif
