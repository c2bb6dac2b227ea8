// A command's parameters declared once, for every front end: each parameter's name, type, unit,
// default, range or choices, short label, help, which front ends show it, and how a value given
// as text is checked and stored. The command line's options (cli/), the Python keywords and
// signatures (python/) and the QGIS parameters (qgis/, through `demlight options --json`) are
// made from the declaration, and each front end spells a parameter its own way: --max-distance,
// max_distance=, "Max distance (m)".
//
// Texts (help, messages) name other parameters as {snake_name}; a front end renders each such
// name in its own spelling (renderNames). The model is GDAL's algorithm framework
// (gdalalgorithm.h: each argument declared once with AddArg, then set from a command line or from
// Python by keyword).
#pragma once

#include "demlight/core/error.h"

#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace demlight {

/// The front ends a parameter is shown in (a bit set).
enum FrontEnd : unsigned {
    kCommandLine = 1,
    kPython = 2,
    kQgis = 4,
    kAllFrontEnds = kCommandLine | kPython | kQgis,
};

/// How a front end spells parameter names in text.
enum class Naming {
    CommandLine,  ///< --max-distance
    Python,       ///< max_distance
    Qgis,         ///< "Max distance (m)" (the label)
    Plain,        ///< max_distance (the declaration's name)
};

/// What a parameter's values are.
enum class ValueKind {
    Number,   ///< a finite real number
    Integer,  ///< a whole number >= 0
    Text,     ///< any text (paths, times, names)
    Flag,     ///< on when given; takes no value
};

struct ValueRange {
    double lo = 0, hi = 0;
    bool lowOpen = false;  ///< lo itself excluded
};

/// One parameter of a command.
struct Parameter {
    std::string name;                  ///< snake_case; the Python keyword, --name-with-dashes
    std::vector<std::string> aliases;  ///< older spellings, snake_case
    std::string cliFlags;              ///< the command line's names when not --name ("-o,--output")
    std::string pythonName;            ///< the Python name when not `name` (output: "path")
    bool positional = false;           ///< the command line's positional argument (the DEM)
    ValueKind kind = ValueKind::Text;
    std::string typeName;              ///< for --help: FLOAT, UINT, TEXT, PATH, TIME, ...
    int minValues = 1, maxValues = 1;  ///< values per use; maxValues -1: repeatable
    bool negative = false;             ///< an Integer may be negative (a signed target)
    std::optional<std::string> defaultText;
    std::optional<ValueRange> range;
    std::vector<std::string> choices;
    bool required = false;
    std::vector<std::string> excludes;  ///< parameters it cannot be combined with
    std::vector<std::string> needs;     ///< parameters it is given with
    std::vector<std::string> fields;    ///< request fields it sets (FieldError::field)
    std::string label;                  ///< short, for forms (at most 40 characters)
    std::string help;                   ///< one line or a few sentences; names as {name}
    std::string unit;                   ///< of a number: m, deg, hPa, ...
    unsigned frontEnds = kAllFrontEnds;
    bool advanced = false;              ///< how the job runs rather than what it computes
    /// Checks one value given as text and may rewrite it (a choice in its canonical case);
    /// returns the problem, empty when none. Runs after the kind, range and choice checks.
    std::function<std::string(std::string&)> extraCheck;
    /// Stores the values of one use (checked already); a flag gets none.
    std::function<void(const std::vector<std::string>&)> store;

    // Declaration, fluent.
    Parameter& alias(std::string a) { aliases.push_back(std::move(a)); return *this; }
    Parameter& flags(std::string f) { cliFlags = std::move(f); return *this; }
    /// The command line's positional argument, shown as `cliName` ("DEM").
    Parameter& positionalAs(std::string cliName) { positional = true; cliFlags = std::move(cliName); return *this; }
    Parameter& inPython(std::string n) { pythonName = std::move(n); return *this; }
    Parameter& type(std::string t) { typeName = std::move(t); return *this; }
    Parameter& values(int least, int most) { minValues = least; maxValues = most; return *this; }
    Parameter& repeatable() { maxValues = -1; return *this; }
    Parameter& byDefault(std::string text) { defaultText = std::move(text); return *this; }
    /// No default shown (the variable's initial value means "not given").
    Parameter& noDefault() { defaultText.reset(); return *this; }
    Parameter& within(double lo, double hi, bool lowOpen = false) { range = ValueRange{lo, hi, lowOpen}; return *this; }
    Parameter& oneOf(std::vector<std::string> c) { choices = std::move(c); return *this; }
    Parameter& mandatory() { required = true; return *this; }
    Parameter& notWith(std::string other) { excludes.push_back(std::move(other)); return *this; }
    Parameter& onlyWith(std::string other) { needs.push_back(std::move(other)); return *this; }
    Parameter& field(std::string f) { fields.push_back(std::move(f)); return *this; }
    Parameter& inUnit(std::string u) { unit = std::move(u); return *this; }
    Parameter& only(unsigned ends) { frontEnds = ends; return *this; }
    Parameter& forHowItRuns() { advanced = true; return *this; }
    Parameter& check(std::function<std::string(std::string&)> f) { extraCheck = std::move(f); return *this; }

    bool shownIn(FrontEnd end) const { return (frontEnds & end) != 0; }
    /// The problem with one value as text (kind, range, choices, extraCheck), empty when none;
    /// `value` may be rewritten to its canonical form.
    std::string problem(std::string& value) const;
    /// What values it takes, for --help: "[0, 20]", "NUMBER > 0", "{auto,full}"; empty for any.
    std::string checkText() const;
    /// The name as `naming` spells it: --max-distance (-o for output), max_distance, the label.
    std::string spelt(Naming naming) const;
    /// Every command-line name: "--max-distance", "--directions", "-o", ...
    std::vector<std::string> commandLineNames() const;
};

/// A command's declaration: its name, what it does, and its parameters in the order a form or
/// --help shows them. Parameters store into variables the declaring code owns, which must outlive
/// the set (a command's values object holds both).
class ParameterSet {
public:
    ParameterSet(std::string command, std::string description)
        : command_(std::move(command)), description_(std::move(description)) {}
    ParameterSet(const ParameterSet&) = delete;
    ParameterSet& operator=(const ParameterSet&) = delete;

    const std::string& command() const { return command_; }
    const std::string& description() const { return description_; }

    /// A parameter that stores into `target` (double, int, size_t, string, bool flag, optional
    /// or vector of these); its kind and type name follow from the target's type.
    template <class T>
    Parameter& add(std::string name, T& target, std::string label, std::string help);
    /// A parameter stored by `store` (one text value per use).
    Parameter& addText(std::string name, std::function<void(const std::string&)> store, std::string label,
                       std::string help);
    /// A parameter without storage (a front end handles it: the DEM, the output).
    Parameter& addBare(std::string name, ValueKind kind, std::string label, std::string help);

    /// The parameter of this name or alias (any front end's), or null.
    const Parameter* find(const std::string& name) const;
    Parameter* find(const std::string& name) {
        return const_cast<Parameter*>(static_cast<const ParameterSet*>(this)->find(name));
    }
    /// The parameter that sets request field `field` (FieldError::field), or null.
    const Parameter* forField(const std::string& field) const;
    const std::deque<Parameter>& parameters() const { return parameters_; }
    std::deque<Parameter>& parameters() { return parameters_; }

    /// Sets parameter `name` (name or alias) from a front end's text values: each checked, then
    /// stored; problems throw ParameterError naming the parameter.
    void set(const std::string& name, std::vector<std::string> values, FrontEnd end);
    /// Throws ParameterError for a required parameter of `end` not set through set().
    void checkRequired(FrontEnd end) const;

private:
    Parameter& push(Parameter p);

    std::string command_, description_;
    std::deque<Parameter> parameters_;  // a deque: the front ends keep pointers to parameters
    std::vector<std::string> given_;
};

/// `text` with each {name} that is a parameter of `set` spelt as `naming` spells it, and other
/// {name}s as spelt by the command-line convention (--name) or plainly.
std::string renderNames(const std::string& text, const ParameterSet* set, Naming naming);

/// The message of an error for a front end: a ParameterError's names and a FieldError's field
/// spelt as `naming` spells the parameters of `set` (the running command's; may be null).
std::string describeError(const std::exception& e, const ParameterSet* set, Naming naming);

/// The declarations as JSON text: {"commands": [{"name", "description", "options": [...]}]},
/// each option with its name, keyword (Python), flags (command line), label, unit, help as each
/// front end renders it (description: the command line's, python_help, qgis_help), type,
/// choices, range, default, values per use, required, excludes, advanced and front_ends. What
/// `demlight options --json` extends and the Python package reads (docs/commands.md).
std::string declarationsJson(const std::vector<const ParameterSet*>& sets);

/// A number as text the way declarations show defaults ("0.13", "16", "inf").
std::string defaultNumberText(double v);

// ---- Implementation of add<T> --------------------------------------------------------------

namespace parameter_detail {
template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type {};
template <class T> struct IsVector : std::false_type {};
template <class T> struct IsVector<std::vector<T>> : std::true_type {};

/// `text` (checked already) as a T.
template <class T>
T fromText(const std::string& text) {
    if constexpr (std::is_same_v<T, std::string>) {
        return text;
    } else if constexpr (std::is_floating_point_v<T>) {
        return static_cast<T>(std::stod(text));
    } else {
        static_assert(std::is_integral_v<T>);
        // problem() has refused a negative value for an unsigned target.
        if constexpr (std::is_signed_v<T>) return static_cast<T>(std::stoll(text));
        else return static_cast<T>(std::stoull(text));
    }
}

template <class T>
constexpr ValueKind kindOf() {
    if constexpr (std::is_same_v<T, std::string>) return ValueKind::Text;
    else if constexpr (std::is_floating_point_v<T>) return ValueKind::Number;
    else return ValueKind::Integer;
}

template <class T>
const char* typeNameOf() {
    if constexpr (std::is_same_v<T, std::string>) return "TEXT";
    else if constexpr (std::is_floating_point_v<T>) return "FLOAT";
    else if constexpr (std::is_signed_v<T>) return "INT";
    else return "UINT";
}
}  // namespace parameter_detail

template <class T>
Parameter& ParameterSet::add(std::string name, T& target, std::string label, std::string help) {
    using namespace parameter_detail;
    Parameter p;
    p.name = std::move(name);
    p.label = std::move(label);
    p.help = std::move(help);
    if constexpr (std::is_same_v<T, bool>) {
        p.kind = ValueKind::Flag;
        p.minValues = p.maxValues = 0;
        p.store = [&target](const std::vector<std::string>&) { target = true; };
    } else if constexpr (IsOptional<T>::value) {
        using V = typename T::value_type;
        p.kind = kindOf<V>();
        p.typeName = typeNameOf<V>();
        if constexpr (std::is_integral_v<V>) p.negative = std::is_signed_v<V>;
        p.store = [&target](const std::vector<std::string>& v) { target = fromText<V>(v.front()); };
    } else if constexpr (IsVector<T>::value) {
        using V = typename T::value_type;
        p.kind = kindOf<V>();
        p.typeName = typeNameOf<V>();
        p.maxValues = -1;
        p.store = [&target](const std::vector<std::string>& v) {
            target.clear();  // the values of all uses come at once, and replace a default
            for (const std::string& s : v) target.push_back(fromText<V>(s));
        };
    } else {
        p.kind = kindOf<T>();
        p.typeName = typeNameOf<T>();
        if constexpr (std::is_integral_v<T>) p.negative = std::is_signed_v<T>;
        p.store = [&target](const std::vector<std::string>& v) { target = fromText<T>(v.front()); };
        if constexpr (std::is_same_v<T, std::string>) {
            if (!target.empty()) p.defaultText = target;
        } else {
            p.defaultText = defaultNumberText(static_cast<double>(target));
        }
    }
    return push(std::move(p));
}

}  // namespace demlight
