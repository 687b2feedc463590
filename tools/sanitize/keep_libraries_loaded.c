/* Preloaded into the sanitizer run of the test suite (tools/tumble test
 * with TUMBLE_PRESET=asan): dlclose does nothing, so a library that was
 * loaded stays mapped, with its globals, until LeakSanitizer looks for
 * leaks at exit.
 *
 * Mesa's OpenGL driver is loaded with dlopen and closed when SDL and EGL
 * shut down, and some of its allocations are still pointed to only from
 * its own globals then. Once it is unmapped, LeakSanitizer reports them as
 * leaked (240 bytes in every GL test) with frames it can only print as
 * "<unknown module>", which no suppression can name. With the driver still
 * mapped, the memory is reachable and nothing needs suppressing: a leak in
 * Tumble's code or in any library is still reported and fails its test. */
int dlclose(void *handle) {
  (void)handle;
  return 0;
}
