#pragma once
// A technique's exception names the phase it came from, so that a failed
// job's reason (and its console line) says where to look:
// "pcss: render: <message>". The phases: prepare (its creation and
// prepare()), render (its frames) and read-back (reading its V).
#include <exception>
#include <string>
#include <utility>

#include "core/error.h"

namespace sb::run {

// Runs `work`, rethrowing whatever it throws as JobError("<technique>:
// <phase>: <what>").
template <class Work>
decltype(auto) in_technique_phase(const std::string& technique, const char* phase, Work&& work) {
  try {
    return std::forward<Work>(work)();
  } catch (const std::exception& e) {
    throw core::JobError(technique + ": " + phase + ": " + e.what());
  }
}

}  // namespace sb::run
