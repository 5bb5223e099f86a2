// What the two incremental Gaussian blurs share (sss_gaussians.comp in screen space,
// sss_texture.comp in texture space): the fit's variances and the tap layout of one 1D
// step. Not shared with C++.
#ifndef SSS_SHADERS_GAUSSIAN_BLUR_GLSL
#define SSS_SHADERS_GAUSSIAN_BLUR_GLSL

// Needs: materials (GpuMaterial[]).

// v_g of material id in mm², 0 for g < 0 (the step before the first Gaussian).
float variance(int id, int g) { return g < 0 ? 0.0 : materials[id].variances[g / 4][g % 4]; }

// The taps of a 1D Gaussian of `sigma` samples (pixels or texels): offsets k x stride for
// k in [-half_taps, half_taps], weights exp(-offset² x inv_two_var), normalised by their sum.
// Reach 4 sigma (truncation: 6e-5 of the mass, 0.03% of the variance); wider Gaussians
// are sampled with an integer stride so that at most SSS_GAUSSIAN_HALF_TAPS taps lie on
// each side. blurs() is false for sigma <= 0.05 (the step is the identity).
struct GaussianTaps {
  bool blurs;
  int half_taps;
  int stride;
  float inv_two_var;
};
GaussianTaps gaussian_taps(float sigma) {
  GaussianTaps t;
  t.blurs = sigma > 0.05;
  float reach = 4.0 * sigma;
  t.half_taps = min(int(ceil(reach)), SSS_GAUSSIAN_HALF_TAPS);
  t.stride = max(1, int(ceil(reach / float(SSS_GAUSSIAN_HALF_TAPS))));
  t.inv_two_var = 1.0 / (2.0 * sigma * sigma);
  return t;
}

#endif
