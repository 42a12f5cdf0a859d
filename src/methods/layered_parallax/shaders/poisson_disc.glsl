// poisson_disc.glsl: 12 points of a Poisson disc of radius 1 (Oat 2006's kernel shape: no two closer than about
// 0.4), with the centre as a 13th tap.
const int kPoissonTaps = 13;
const vec2 kPoissonDisc[13] = vec2[13](
    vec2(0.0f, 0.0f), vec2(-0.326f, -0.406f), vec2(-0.840f, -0.074f), vec2(-0.696f, 0.457f), vec2(-0.203f, 0.621f),
    vec2(0.962f, -0.195f), vec2(0.473f, -0.480f), vec2(0.519f, 0.767f), vec2(0.185f, -0.893f),
    vec2(0.507f, 0.064f), vec2(0.896f, 0.412f), vec2(-0.322f, -0.933f), vec2(-0.792f, -0.598f));
