// Strict parsing of numeric command-line values, shared by every executable:
// the whole argument must be the number, inside its range, and finite;
// otherwise one InputError naming the flag, the range and what was given.
#pragma once

#include <string>

namespace pt {

/// A whole number in [lo, hi]; "expected a whole number >= lo" when hi is huge.
long long parse_whole_number(const std::string& flag, const std::string& text, long long lo,
                             long long hi);

/// A finite number >= lo (> lo when open_lo) and <= hi.
double parse_real_number(const std::string& flag, const std::string& text, double lo,
                         double hi = 1e308, bool open_lo = false);

}  // namespace pt
