#include "demlight/run/parameters.h"

#include "demlight/run/options.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace demlight {

namespace {

std::string dashed(std::string name) {
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
}

std::string numberText(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

/// "[0, 20]" or "(0, 1]"; "NUMBER > 0" when unbounded above.
std::string rangeText(const ValueRange& r) {
    if (std::isfinite(r.hi))
        return std::string(r.lowOpen ? "(" : "[") + numberText(r.lo) + ", " + numberText(r.hi) + "]";
    return std::string(r.lowOpen ? "NUMBER > " : "NUMBER >= ") + numberText(r.lo);
}

std::string rangeProblem(const ValueRange& r, double v, const std::string& text) {
    if (!(v < r.lo || v > r.hi || (r.lowOpen && v == r.lo))) return {};
    if (std::isfinite(r.hi)) return "value " + text + " is outside " + rangeText(r);
    return std::string("must be ") + (r.lowOpen ? "> " : ">= ") + numberText(r.lo) + ", got " + text;
}

/// Digits, with a leading minus sign allowed (a negative value is then refused by the range,
/// naming its bound).
bool wholeNumber(const std::string& text) {
    const std::size_t first = !text.empty() && text[0] == '-' ? 1 : 0;
    return text.size() > first && text.size() < 20 &&
           std::all_of(text.begin() + long(first), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::string defaultNumberText(double v) { return numberText(v); }

std::string Parameter::checkText() const {
    if (!choices.empty()) {
        std::string list;
        for (const std::string& c : choices) list += (list.empty() ? "" : ",") + c;
        return "{" + list + "}";
    }
    return range ? rangeText(*range) : std::string();
}

std::string Parameter::problem(std::string& value) const {
    if (kind == ValueKind::Number || kind == ValueKind::Integer) {
        std::optional<double> v;
        if (kind == ValueKind::Integer) {
            if (!wholeNumber(value)) return "expected a whole number, got '" + value + "'";
            v = std::stod(value);
            if (*v < 0 && !negative && !range) return "must be >= 0, got " + value;
        } else {
            v = parseFiniteNumber(value);
            if (!v) return "expected a finite number, got '" + value + "'";
        }
        if (range) {
            if (std::string p = rangeProblem(*range, *v, value); !p.empty()) return p;
        }
    }
    if (extraCheck) {
        if (std::string p = extraCheck(value); !p.empty()) return p;
    }
    if (!choices.empty() && std::find(choices.begin(), choices.end(), value) == choices.end()) {
        std::string list;
        for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
        return "'" + value + "' is not one of " + list;
    }
    return {};
}

std::vector<std::string> Parameter::commandLineNames() const {
    std::vector<std::string> out;
    if (!cliFlags.empty()) {
        std::stringstream s(cliFlags);
        for (std::string part; std::getline(s, part, ',');) out.push_back(part);
        return out;
    }
    out.push_back("--" + dashed(name));
    for (const std::string& a : aliases) out.push_back("--" + dashed(a));
    return out;
}

std::string Parameter::spelt(Naming naming) const {
    switch (naming) {
    case Naming::CommandLine: return positional ? cliFlags : commandLineNames().front();
    case Naming::Python: return pythonName.empty() ? name : pythonName;
    case Naming::Qgis: return "\"" + label + "\"";
    case Naming::Plain: break;
    }
    return name;
}

Parameter& ParameterSet::push(Parameter p) {
    if (find(p.name)) throw Error("parameter '" + p.name + "' of " + command_ + " is declared twice");
    parameters_.push_back(std::move(p));
    return parameters_.back();
}

Parameter& ParameterSet::addText(std::string name, std::function<void(const std::string&)> store, std::string label,
                                 std::string help) {
    Parameter p;
    p.name = std::move(name);
    p.kind = ValueKind::Text;
    p.typeName = "TEXT";
    p.label = std::move(label);
    p.help = std::move(help);
    p.store = [store = std::move(store)](const std::vector<std::string>& v) { store(v.front()); };
    return push(std::move(p));
}

Parameter& ParameterSet::addBare(std::string name, ValueKind kind, std::string label, std::string help) {
    Parameter p;
    p.name = std::move(name);
    p.kind = kind;
    p.typeName = kind == ValueKind::Flag ? "" : "TEXT";
    if (kind == ValueKind::Flag) p.minValues = p.maxValues = 0;
    p.label = std::move(label);
    p.help = std::move(help);
    p.store = [](const std::vector<std::string>&) {};
    return push(std::move(p));
}

const Parameter* ParameterSet::find(const std::string& name) const {
    for (const Parameter& p : parameters_) {
        if (p.name == name || (!p.pythonName.empty() && p.pythonName == name)) return &p;
        if (std::find(p.aliases.begin(), p.aliases.end(), name) != p.aliases.end()) return &p;
    }
    return nullptr;
}

const Parameter* ParameterSet::forField(const std::string& field) const {
    for (const Parameter& p : parameters_)
        if (std::find(p.fields.begin(), p.fields.end(), field) != p.fields.end()) return &p;
    // A field named as its parameter: albedoRaster is albedo_raster.
    std::string snake;
    for (char c : field) {
        if (c >= 'A' && c <= 'Z') {
            snake += '_';
            snake += char(c - 'A' + 'a');
        } else {
            snake += c;
        }
    }
    return find(snake);
}

void ParameterSet::set(const std::string& name, std::vector<std::string> values, FrontEnd end) {
    const Parameter* p = find(name);
    if (!p || !p->shownIn(end)) throw ParameterError(command_ + " has no parameter " + name);
    const std::size_t n = values.size();
    const bool countOk = p->maxValues < 0 ? n >= 1 : (n >= std::size_t(p->minValues) && n <= std::size_t(p->maxValues));
    if (!countOk)
        throw ParameterError("{" + p->name + "}: expected " +
                             (p->maxValues < 0 ? std::string("one or more values")
                                               : std::to_string(p->maxValues) + (p->maxValues == 1 ? " value" : " values")) +
                             ", got " + std::to_string(n));
    for (std::string& v : values)
        if (std::string problem = p->problem(v); !problem.empty()) throw ParameterError("{" + p->name + "}: " + problem);
    p->store(values);
    given_.push_back(p->name);
}

void ParameterSet::checkRequired(FrontEnd end) const {
    for (const Parameter& p : parameters_)
        if (p.required && p.shownIn(end) && std::find(given_.begin(), given_.end(), p.name) == given_.end())
            throw ParameterError("{" + p.name + "} is required");
}

std::string renderNames(const std::string& text, const ParameterSet* set, Naming naming) {
    return renderNames(text, [&](const std::string& name) {
        if (const Parameter* p = set ? set->find(name) : nullptr) {
            // An older spelling named as itself ("{directions} is the older spelling").
            if (p->name != name && naming == Naming::CommandLine) return "--" + dashed(name);
            if (p->name != name && naming != Naming::Qgis) return name;
            return p->spelt(naming);
        }
        return naming == Naming::CommandLine ? "--" + dashed(name) : name;
    });
}

std::string describeError(const std::exception& e, const ParameterSet* set, Naming naming) {
    if (const auto* named = dynamic_cast<const ParameterError*>(&e)) return renderNames(named->text(), set, naming);
    if (const auto* field = dynamic_cast<const FieldError*>(&e)) {
        if (const Parameter* p = set ? set->forField(field->field()) : nullptr) return p->spelt(naming) + field->detail();
        return field->what();
    }
    return e.what();
}

namespace {

const char* kindName(const Parameter& p) {
    if (!p.typeName.empty()) return p.typeName.c_str();
    return p.kind == ValueKind::Flag ? "" : "TEXT";
}

nlohmann::ordered_json describe(const Parameter& p, const ParameterSet& set) {
    nlohmann::ordered_json j;
    j["name"] = p.name;
    j["keyword"] = p.spelt(Naming::Python);
    j["aliases"] = p.aliases;
    j["flags"] = p.positional ? std::vector<std::string>{} : p.commandLineNames();
    j["positional"] = p.positional;
    j["label"] = p.label;
    j["unit"] = p.unit;
    j["description"] = renderNames(p.help, &set, Naming::CommandLine);
    j["python_help"] = renderNames(p.help, &set, Naming::Python);
    j["qgis_help"] = renderNames(p.help, &set, Naming::Qgis);
    j["default"] = p.defaultText ? nlohmann::ordered_json(*p.defaultText) : nlohmann::ordered_json();
    j["required"] = p.required;
    j["flag"] = p.kind == ValueKind::Flag;
    j["type"] = p.kind == ValueKind::Number    ? "FLOAT"
                : p.kind == ValueKind::Integer ? "INT"
                : p.kind == ValueKind::Flag    ? ""
                                               : kindName(p);
    j["choices"] = p.choices;
    if (p.range) {
        j["range"] = {{"min", p.range->lo}, {"max", std::isfinite(p.range->hi) ? nlohmann::ordered_json(p.range->hi)
                                                                                 : nlohmann::ordered_json()},
                      {"min_open", p.range->lowOpen}};
    } else {
        j["range"] = nullptr;
    }
    j["min_values"] = p.minValues;
    j["max_values"] = p.maxValues;
    j["excludes"] = p.excludes;
    j["advanced"] = p.advanced;
    nlohmann::ordered_json ends = nlohmann::ordered_json::array();
    if (p.shownIn(kCommandLine)) ends.push_back("cli");
    if (p.shownIn(kPython)) ends.push_back("python");
    if (p.shownIn(kQgis)) ends.push_back("qgis");
    j["front_ends"] = ends;
    return j;
}

}  // namespace

std::string declarationsJson(const std::vector<const ParameterSet*>& sets) {
    nlohmann::ordered_json commands = nlohmann::ordered_json::array();
    for (const ParameterSet* set : sets) {
        nlohmann::ordered_json c;
        c["name"] = set->command();
        c["description"] = set->description();
        nlohmann::ordered_json options = nlohmann::ordered_json::array();
        for (const Parameter& p : set->parameters()) options.push_back(describe(p, *set));
        c["options"] = options;
        commands.push_back(c);
    }
    nlohmann::ordered_json root;
    root["commands"] = commands;
    return root.dump(1);
}

}  // namespace demlight
