#define PROBE_SCALE 2.5
