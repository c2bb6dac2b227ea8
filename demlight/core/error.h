// The one exception family of demlight. The library throws; the CLI catches once in main.
#pragma once

#include <functional>
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

/// `text` with each {name} (a name is [a-z][a-z0-9_]*) replaced by spell(name); other braces are
/// left as they are. The one reader of parameter names in messages and help texts.
std::string renderNames(const std::string& text, const std::function<std::string(const std::string&)>& spell);

/// An Error whose message names parameters as {snake_name} ("{z_unit} \"furlong\" is not a
/// vertical unit"): each front end renders the names its own way (demlight/run/parameters.h:
/// --z-unit, z_unit=, "Vertical unit"); what() names them plainly (z_unit).
class ParameterError : public Error {
public:
    explicit ParameterError(std::string text)
        : Error(renderNames(text, [](const std::string& name) { return name; })), text_(std::move(text)) {}
    /// The message with its {name}s.
    const std::string& text() const { return text_; }

private:
    std::string text_;
};

/// Raised when a progress callback asks to stop.
class Cancelled : public Error {
public:
    Cancelled() : Error("cancelled") {}
};

}  // namespace demlight
