// The one exception family of demlight. The library throws; the CLI catches once in main.
#pragma once

#include <stdexcept>
#include <string>

namespace demlight {

/// Any failure the user can act on: bad input file, bad option, unwritable output.
/// Messages name the file or option and what was expected.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Raised when a progress callback asks to stop.
class Cancelled : public Error {
public:
    Cancelled() : Error("cancelled") {}
};

}  // namespace demlight
