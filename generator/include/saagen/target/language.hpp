// The source languages that target tables name, and the shader stages and client APIs the
// compiler (saagen/validate/compiler.hpp) takes. A language is data: its table
// targets/<language>/language.json, beside its skeletons, names the printer of its function bodies
// (saagen/print/backend.hpp) and how its emitted files are validated (glslang's front end and its
// settings, or Tint through the WebGPU runner), so that no code compares languages.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

enum class ShaderStage { vertex, fragment, compute };
// The API that consumes the SPIR-V. GLSL can target both; HLSL targets Vulkan only.
// opengl_es is source-level only: GLSL ES 3.00 (WebGL2, OpenGL ES 3.0) has no SPIR-V form, so
// glslang's ES front end parses and links it, and no module is produced.
enum class ClientApi { vulkan, opengl, opengl_es };

// How glslang compiles a language in process (saagen/validate/compiler.hpp).
struct GlslangFrontEnd {
  bool hlsl = false;                // glslang's HLSL front end (else its GLSL one)
  int default_version = 450;        // the version of a source without a #version line
  bool named_entry_points = false;  // the entry function may have any name (GLSL's is always main)
};

// One language table.
struct Language {
  std::string name;         // what target tables name it by ("language")
  std::string description;  // one line
  std::string printer;      // the printer of its function bodies (saagen/print/backend.hpp)
  // Set where glslang compiles the language to SPIR-V ("validator": "glslang"), so that its emitted
  // files are validated in process (glslang and spirv-val); unset where Tint validates them through
  // the WebGPU runner ("validator": "tint").
  std::optional<GlslangFrontEnd> glslang;
  std::string table;  // the table's path under the source tree, for messages

  bool compiled_in_process() const { return glslang.has_value(); }
  // The front end; throws saagen::Error when glslang does not compile the language.
  const GlslangFrontEnd& front_end() const;
  // Parses one table; throws saagen::Error naming `source` on a missing or malformed key.
  static Language parse(std::string_view json_text, std::string_view source);
};

// One of this build's language tables (compared by identity), as a target table or a request names it.
class SourceLanguage {
 public:
  // The language of that name; throws saagen::Error when no table of this build names it.
  static SourceLanguage named(std::string_view name);

  const Language& operator*() const { return *language_; }
  const Language* operator->() const { return language_; }
  std::string_view name() const { return language_->name; }
  friend bool operator==(SourceLanguage a, SourceLanguage b) { return a.language_ == b.language_; }

 private:
  explicit SourceLanguage(const Language* language) : language_(language) {}
  const Language* language_;
  friend std::optional<SourceLanguage> source_language(std::string_view name);
};

// The language a target table's "language" names, or nothing when this build has no table of it.
std::optional<SourceLanguage> source_language(std::string_view name);
// The names of this build's languages, in name order.
std::vector<std::string> language_names();

}  // namespace saagen
