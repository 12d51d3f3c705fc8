#pragma once
// Adjusted p-values for a family of tests, so that `compare` can judge many
// jobs at one alpha: without a correction, 50 unchanged jobs, each tested
// at 0.02 and failing the run when slower (half of the rejections), fail it
// in up to 1 - 0.99^50 = 39.5 % of the runs (30 % measured; docs/ci.md,
// "Many jobs, one alpha").
//   - Holm (1979), step-down: with p sorted ascending, p~(i) =
//     max over j <= i of min(1, (m - j + 1) p(j)). Rejecting p~ < alpha keeps
//     the chance of ANY false rejection (family-wise error rate) <= alpha,
//     under any dependence between the tests.
//   - Benjamini-Hochberg (1995), step-up: p~(i) = min over j >= i of
//     min(1, m p(j) / j). Keeps the expected share of false rejections among
//     the rejections (false discovery rate) <= alpha for independent or
//     positively dependent tests; when every job is unchanged that is the
//     family-wise rate too.
//   - none: p~ = p.
// Each adjusted value is returned at its input's position.
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sb::results {

enum class Correction { kHolm, kBenjaminiHochberg, kNone };

// "holm", "bh" or "none"; nullopt otherwise.
std::optional<Correction> parse_correction(const std::string& name);
const char* to_string(Correction c);
// "Holm", "Benjamini-Hochberg", "no" (as in "no correction"): for messages.
const char* correction_name(Correction c);

// Throws std::invalid_argument for a p outside [0, 1] or NaN.
std::vector<double> adjust_p_values(std::span<const double> p, Correction c);

}  // namespace sb::results
