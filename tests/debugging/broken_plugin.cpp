// A technique plugin that fails on purpose, for tests/debugging only (never
// installed), built like an outside plugin on the plugin API and the
// shadow-map kit:
//   mode=typo    prepare() compiles a lit_fraction() with a syntax error on
//                line kTypoLine of its own GLSL (MapLookupPass);
//   mode=undefined  the same with a name nothing declares on line
//                kUndefinedLine, after the kit's kPcfGlsl as kit GLSL;
//   mode=lines   prepare() throws a message of several lines;
//   mode=null    prepare() writes through a null pointer (SIGSEGV).
// It renders nothing else: its jobs never get past prepare().
#include <memory>
#include <stdexcept>
#include <string>

#include "broken_plugin_glsl.h"
#include "common/glsl_pcf.h"
#include "common/map_lookup.h"
#include "plugin/registry.h"

namespace broken {
namespace {

class Broken final : public sb::Technique {
 public:
  explicit Broken(const sb::Params& p) : mode_(p.get_string("mode")) {}
  void prepare(const sb::FrameInputs& /*in*/) override {
    if (mode_ == "typo") lookup_ = sb::techniques::MapLookupPass("broken_lookup", kTypoGlsl);
    if (mode_ == "undefined")
      lookup_ = sb::techniques::MapLookupPass("broken_lookup", kUndefinedGlsl, false,
                                              sb::techniques::kPcfGlsl);
    if (mode_ == "lines") throw std::runtime_error(kLinesMessage);
    if (mode_ == "null") {
      // Volatile both: the pointer read at run time (no trap made of it),
      // the store kept (GCC 12 drops a plain one).
      volatile int* volatile nowhere = nullptr;
      *nowhere = 1;  // NOLINT(clang-analyzer-core.NullDereference): the crash asked for
    }
  }
  void render(const sb::FrameInputs& /*in*/, sb::gl::PassTimer& /*timer*/) override {}

 private:
  std::string mode_;
  sb::techniques::MapLookupPass lookup_;
};

}  // namespace
}  // namespace broken

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(
      {.name = "broken",
       .family = "broken",
       .summary =
           "test only: fails in prepare(): a GLSL typo or undefined name, a long message, a crash",
       .needs = sb::Needs{},
       .params = {sb::core::choice_param("mode", "typo", {"typo", "undefined", "lines", "null"},
                                         "how")},
       .create = [](const sb::Params& p) { return std::make_unique<broken::Broken>(p); }});
}
