// The one exception family of demlight. The library throws; the CLI catches once in main.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace demlight {

/// Any failure the user can act on: bad input file, bad option, unwritable output.
/// Messages name the file or option and what was expected.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// An Error about one field of a request (a product's or a kernel's parameters): what() is
/// "<field><detail>", e.g. "albedo 2: must be in [0, 1]". Callers that know the field by another
/// name (the CLI: by its flag) say detail() after their own name for it.
class FieldError : public Error {
public:
    FieldError(std::string field, std::string detail)
        : Error(field + detail), field_(std::move(field)), detail_(std::move(detail)) {}
    const std::string& field() const { return field_; }
    /// The message after the field name, starting with its separator (" 2: must be ...").
    const std::string& detail() const { return detail_; }

private:
    std::string field_, detail_;
};

/// Raised when a progress callback asks to stop.
class Cancelled : public Error {
public:
    Cancelled() : Error("cancelled") {}
};

}  // namespace demlight
