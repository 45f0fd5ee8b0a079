/* An engine written in C: Filament's form in perceptual roughness, emitted to memory through the
 * C API. Prints the file's name; one line on stderr and a non-zero exit on failure. */
#include <saagen/saagen.h>
#include <stdio.h>
#include <string.h>

int main(void) {
  char* name = NULL;
  char* text = NULL;
  if (saagen_emit("filament.glsl", &name, &text) != 0) {
    fprintf(stderr, "c_api_consumer: %s\n", saagen_last_error());
    return 1;
  }
  const int ok = strstr(text, "saa_deferred_sum_fragment_perceptual(") != NULL;
  printf("c_api_consumer: %s (%zu bytes)\n", name, strlen(text));
  saagen_free(name);
  saagen_free(text);
  return ok ? 0 : 1;
}
