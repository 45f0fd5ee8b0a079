/* The C API (saagen/saagen.h) used from C: the catalogue as JSON, a variant and a preset emitted
 * to memory, a manifest bundle, and the thread-local one-line error. Compiled as C (C11). */
#include "saagen/saagen.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

#define CHECK(condition)                                                            \
  do {                                                                              \
    if (!(condition)) {                                                             \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
      ++failures;                                                                   \
    }                                                                               \
  } while (0)

static void list_json(void) {
  char* json = NULL;
  CHECK(saagen_list_json(NULL, NULL, &json) == 0);
  CHECK(json && strstr(json, "\"deferred-avg\"") && strstr(json, "\"presets\"") && strstr(json, "\"smoothness\""));
  saagen_free(json);
  json = NULL;
  CHECK(saagen_list_json("eng_", "perceptual", &json) == 0);
  CHECK(json && strstr(json, "eng_deferred_avg_perceptual") && strstr(json, "\"roughness_domain\": \"perceptual\""));
  saagen_free(json);
}

static void emit_variant_and_preset(void) {
  char* name = NULL;
  char* text = NULL;
  CHECK(saagen_emit("deferred-avg.glsl?domain=perceptual", &name, &text) == 0);
  CHECK(name && strcmp(name, "saa_deferred_avg_perceptual.glsl") == 0);
  CHECK(text && strstr(text, "saa_deferred_avg_perceptual(") && strstr(text, "domain=perceptual"));
  saagen_free(name);
  saagen_free(text);
  text = NULL;
  CHECK(saagen_emit("saagen/hdrp.hlsl", NULL, &text) == 0);
  CHECK(text && strstr(text, "saa_deferred_sum_smoothness(") && strstr(text, "sigma2=0.1") && strstr(text, "kappa=0.04"));
  saagen_free(text);
  CHECK(strcmp(saagen_last_error(), "") == 0);
}

static void errors_are_one_line(void) {
  char* text = NULL;
  CHECK(saagen_emit("deferred-avg.glsl?domain=linear", NULL, &text) == -1);
  CHECK(text == NULL);
  CHECK(strcmp(saagen_last_error(),
               "saagen/deferred-avg.glsl?domain=linear: --domain 'linear' is not a roughness domain; use one of alpha2, alpha, "
               "perceptual, smoothness") == 0);
  CHECK(saagen_emit(NULL, NULL, &text) == -1);
  CHECK(strchr(saagen_last_error(), '\n') == NULL && strlen(saagen_last_error()) > 0);
  CHECK(saagen_emit_manifest("name = \"scene\"\ntargets = [\"glsl\"]\ncolour = 1\n", "scene.toml") == NULL);
  CHECK(strncmp(saagen_last_error(), "scene.toml:3:1: unknown key 'colour'", 36) == 0);
}

static void manifest_bundle(void) {
  const char* manifest =
      "name = \"scene\"\n"
      "targets = [\"glsl\", \"hlsl\"]\n"
      "preset = \"filament\"\n"
      "[[material]]\n"
      "name = \"terrain\"\n"
      "path = \"deferred\"\n";
  saagen_files* files = saagen_emit_manifest(manifest, "scene.toml");
  CHECK(files != NULL);
  CHECK(saagen_files_count(files) == 2);
  CHECK(saagen_files_name(files, 0) && strcmp(saagen_files_name(files, 0), "saa_scene_perceptual.glsl") == 0);
  CHECK(saagen_files_text(files, 1) && strstr(saagen_files_text(files, 1), "saa_deferred_sum_fragment_perceptual("));
  CHECK(saagen_files_text(files, 1) && strstr(saagen_files_text(files, 1), "sigma2=0.15"));
  CHECK(saagen_files_name(files, 2) == NULL);
  saagen_files_free(files);
}

int main(void) {
  CHECK(strlen(saagen_version()) > 0);
  list_json();
  emit_variant_and_preset();
  errors_are_one_line();
  manifest_bundle();
  if (failures) {
    fprintf(stderr, "test_c_api: %d check(s) failed\n", failures);
    return 1;
  }
  printf("test_c_api: all checks passed\n");
  return 0;
}
