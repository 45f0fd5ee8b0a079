/* saagen's C API: a stable interface over the library for engines written in C, Rust, C#,
 * Python (ctypes) and others. No C++ type crosses it.
 *
 * Conventions
 *   - Functions returning int return 0 on success and -1 on failure; functions returning a
 *     pointer return NULL on failure. After a failure, saagen_last_error() gives one line
 *     (where, what, what to do); it is thread-local and stays valid until the next saagen call
 *     on the same thread.
 *   - Strings written to a `char** out` are allocated by the library, NUL-terminated, and the
 *     caller frees them with saagen_free(). Nothing is written on failure.
 *   - A saagen_files handle is freed with saagen_files_free(); the strings it returns live as
 *     long as the handle.
 *
 * Emission requests use the include-name grammar of the shader-compiler plugin:
 *   [saagen/]<variant or preset>.<glsl|essl|hlsl>[?key=value(&key=value)*]
 *   keys: prefix, sigma2, kappa, preset, domain (alpha2, alpha, perceptual, smoothness),
 *         precision (fp32, fp16, min16), guards (on, off)
 *   e.g. "deferred-avg.glsl?domain=perceptual", "hdrp.hlsl".
 */
#ifndef SAAGEN_H
#define SAAGEN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Version of this interface; raised only when a function is added. */
#define SAAGEN_C_API_VERSION 1

/* The library version, e.g. "0.1.0" (static storage). */
const char* saagen_version(void);

/* The last failure on this thread as one line, or "" when none (thread-local storage). */
const char* saagen_last_error(void);

/* Frees a string the library wrote to a `char** out`; NULL is allowed. */
void saagen_free(char* text);

/* The catalogue as JSON (`saagen list --json`): variants, functions, options, roughness domains
 * and presets. `prefix` NULL means "saa_"; `domain` NULL means "alpha2". */
int saagen_list_json(const char* prefix, const char* domain, char** out_json);

/* One variant (or preset) emitted to memory: the file's name (e.g. saa_deferred_avg_perceptual.glsl)
 * and its text. `out_file_name` may be NULL. */
int saagen_emit(const char* request, char** out_file_name, char** out_text);

/* A scene manifest (TOML text, the format of `saagen emit --manifest`) planned and emitted to
 * memory: one bundle per target and precision. `source_name` names the text in messages. With a
 * glints = true material the bundles hold the glint BRDF; its dictionary texture (binary, so not
 * among these texts) is what `saagen glints dictionary --count N --lods L --alpha A` writes for
 * the manifest's glint_count, glint_lods and glint_alpha (defaults 192, 16, 0.5). */
typedef struct saagen_files saagen_files;
saagen_files* saagen_emit_manifest(const char* manifest_toml, const char* source_name);
size_t saagen_files_count(const saagen_files* files);
/* NULL when index >= count. */
const char* saagen_files_name(const saagen_files* files, size_t index);
const char* saagen_files_text(const saagen_files* files, size_t index);
void saagen_files_free(saagen_files* files);

#ifdef __cplusplus
}
#endif

#endif /* SAAGEN_H */
