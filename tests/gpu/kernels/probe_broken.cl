/* Deliberately broken kernel: the runtime must report the build log. */
__kernel void probe_broken(__global double *y) { y[0] = undefined_symbol_for_test; }
