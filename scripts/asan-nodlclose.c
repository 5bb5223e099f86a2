/* Preloaded by scripts/test-asan.sh only. The Vulkan loader dlclose()s the ICD (lavapipe)
 * and the layers when an instance is destroyed, so LeakSanitizer, which runs at exit, sees
 * their leaks as "<unknown module>" and a suppression by library name cannot match them.
 * Keeping every library mapped makes each leak name the library it came from. */
int dlclose(void *handle);
int dlclose(void *handle) {
  (void)handle;
  return 0;
}
