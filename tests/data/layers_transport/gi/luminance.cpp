// Fixture for scripts/check-layers (ctest layers.detects_transport_in_host): a host file in
// the integrators layer that computes luminance itself instead of calling ts_luminance.
float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
