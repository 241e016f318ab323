/* LD_PRELOADed by ci/sanitize.sh (built there, without sanitizers): dlclose() does nothing, so every
 * library dlopen()ed during a test - the Mesa GL and Vulkan drivers, the Vulkan loader's layers -
 * stays mapped until the process exits. LeakSanitizer runs at exit: a leak allocated by an
 * unloaded library shows only "<unknown module>" frames, which no suppression can name; kept
 * loaded, its frames name the library and tests/sanitizers/lsan.supp can suppress it by module.
 * It also keeps ASan from misattributing frames to whatever was mapped later at the same address. */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
