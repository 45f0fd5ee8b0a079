// shaderc's include interface for saagen snippets (the name grammar: saagen/integrate/include_handler.hpp),
// in the library saagen::shaderc (links shaderc through pkg-config):
//
//   shaderc::CompileOptions options;
//   options.SetIncluder(std::make_unique<saagen::ShadercIncluder>(saagen::IncludeOptions{.preset = "filament"}));
//
// Names outside saagen/ go to `fallback` when one is given, else fail.
#pragma once

#include "saagen/integrate/include_handler.hpp"

#include <memory>
#include <set>
#include <shaderc/shaderc.hpp>

namespace saagen {

class ShadercIncluder : public shaderc::CompileOptions::IncluderInterface {
 public:
  explicit ShadercIncluder(IncludeOptions defaults = {}, std::unique_ptr<shaderc::CompileOptions::IncluderInterface> fallback = nullptr);

  shaderc_include_result* GetInclude(const char* requested_source, shaderc_include_type type, const char* requesting_source,
                                     size_t include_depth) override;
  void ReleaseInclude(shaderc_include_result* data) override;

 private:
  shaderc_include_result* own(shaderc_include_result* result);
  IncludeOptions defaults_;
  std::set<shaderc_include_result*> owned_;
  std::unique_ptr<shaderc::CompileOptions::IncluderInterface> fallback_;
};

}  // namespace saagen
