// The classic airlight of Sun et al. (eqs. 7-12, as printed) with F(u, v) (eq. 10) read from an
// N x N R32F texture (render FTable::data(): x = u index over [0, 10], y = v index over
// [0, pi/2]) by bilinear interpolation done here in float, clamped to the table. GLSL only.
#ifndef NIMBUS_AIRLIGHT_TABLE_GLSL
#define NIMBUS_AIRLIGHT_TABLE_GLSL

float airlight_table_F(sampler2D F_table, int N, float u, float v) {
  float fu = clamp(u / 10.0, 0.0, 1.0) * float(N - 1);
  float fv = clamp(v / 1.57079633, 0.0, 1.0) * float(N - 1);
  int i = min(int(fu), N - 2);
  int j = min(int(fv), N - 2);
  float du = fu - float(i);
  float dv = fv - float(j);
  float f00 = texelFetch(F_table, ivec2(i, j), 0).r;
  float f10 = texelFetch(F_table, ivec2(i + 1, j), 0).r;
  float f01 = texelFetch(F_table, ivec2(i, j + 1), 0).r;
  float f11 = texelFetch(F_table, ivec2(i + 1, j + 1), 0).r;
  return mix(mix(f00, f10, du), mix(f01, f11, du), dv);
}

// Sun eq. 11 (eq. 12 for Dvp >= 1e30); no guard for sin(gamma) = 0 or beta = 0, as printed.
float airlight_table(sampler2D F_table, int N, float beta, float I0, float Dsv, float Dvp, float cos_gamma,
                     float sin_gamma) {
  float Tsv = beta * Dsv;
  float Tvp = beta * Dvp;
  float A0 = beta * beta * I0 * exp(-Tsv * cos_gamma) / (6.28318531 * Tsv * sin_gamma);  // eq. 7
  float A1 = Tsv * sin_gamma;                                                             // eq. 8
  float v1 = Dvp >= 1.0e30 ? 1.57079633 : 0.78539816 + 0.5 * atan((Tvp - Tsv * cos_gamma) / (Tsv * sin_gamma));
  float half_gamma = 0.5 * atan(sin_gamma, cos_gamma);
  return A0 * (airlight_table_F(F_table, N, A1, v1) - airlight_table_F(F_table, N, A1, half_gamma));
}

#endif
