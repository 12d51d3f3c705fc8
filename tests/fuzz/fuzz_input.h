#pragma once
// What every fuzz target asserts: bad input ends in an InputError (which
// names the file and the place, and which the CLI turns into exit code 2),
// never in another exception, a crash, a leak or undefined behaviour (ASan
// and UBSan watch those). Anything else aborts, so libFuzzer keeps the input.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/error.h"

namespace sb::fuzz {

template <class Body>
int expect_only_input_errors(const char* target, Body&& body) {
  try {
    body();
  } catch (const core::InputError&) {
    // The documented answer to bad input.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: bad input ended in an exception that is not an InputError: %s\n",
                 target, e.what());
    std::abort();
  }
  return 0;
}

}  // namespace sb::fuzz
