// Fragment precision. The 16-bit depth packing needs highp (mediump floats hold only 11 significant bits); the
// renderer checks GL_HIGH_FLOAT support before building any program and refuses a context without it.
// Samplers default to lowp in fragment shaders; fetching packed bytes at highp keeps every byte exact however the
// implementation stores lowp.
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
precision highp sampler2D;
#else
precision mediump float;
#endif
