// A formula rule's checks, made before anything is compiled or run.

#include "sim/formula/rule.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sim::formula {

FormulaError::FormulaError(Pos pos, const std::string& what)
    : std::invalid_argument("line " + std::to_string(pos.line) + ", column " + std::to_string(pos.column) + ": " +
                            what),
      pos_(pos),
      message_(what) {}

std::string chemical_name(int i) {
    if (i < 0 || i >= max_chemicals) throw std::invalid_argument("chemical index " + std::to_string(i));
    return std::string(1, static_cast<char>('a' + i));
}

int dimensionality(int width, int height, int depth) {
    const int n = (width > 1) + (height > 1) + (depth > 1);
    return n == 0 ? 1 : n;
}

int stages(Integrator integrator) {
    switch (integrator) {
    case Integrator::euler: return 1;
    case Integrator::heun: return 2;
    case Integrator::rk4: return 4;
    }
    return 1;
}

int order(Integrator integrator) {
    switch (integrator) {
    case Integrator::euler: return 1;
    case Integrator::heun: return 2;
    case Integrator::rk4: return 4;
    }
    return 1;
}

const char* integrator_name(Integrator integrator) {
    switch (integrator) {
    case Integrator::euler: return "euler";
    case Integrator::heun: return "heun";
    case Integrator::rk4: return "rk4";
    }
    return "euler";
}

const char* edge_name(Edge edge) {
    switch (edge) {
    case Edge::periodic: return "periodic";
    case Edge::clamped: return "clamped";
    case Edge::neumann: return "neumann";
    case Edge::dirichlet: return "dirichlet";
    }
    return "periodic";
}

const char* side_name(int side) {
    static const char* const names[6] = {"left", "right", "bottom", "top", "back", "front"};
    return side >= 0 && side < 6 ? names[side] : "?";
}

Edges Edges::all(Edge edge, const std::vector<double>& value) {
    Edges e;
    for (Of& of : e.side) {
        of.edge = edge;
        if (edge == Edge::dirichlet) of.value = value;
    }
    return e;
}

Edges Rule::own_edges() const {
    if (edges) return *edges;
    return Edges::all(wrap ? Edge::periodic : Edge::clamped);
}

double formula_value(double parameter) {
    char text[64];
    std::snprintf(text, sizeof text, "%.8f", static_cast<double>(static_cast<float>(parameter)));
    return std::strtod(text, nullptr);
}

void Rule::set_parameter(const std::string& name, double value) {
    for (auto it = parameters.rbegin(); it != parameters.rend(); ++it)
        if (it->first == name) {
            it->second = value;
            return;
        }
    parameters.emplace_back(name, value);
}

double Rule::parameter(const std::string& name, double fallback) const {
    double value = fallback;
    for (const auto& [key, v] : parameters)
        if (key == name) value = v;
    return value;
}

void Rule::validate(int width, int height, int depth) const {
    if (chemicals < 1 || chemicals > max_chemicals)
        throw std::invalid_argument("number_of_chemicals is " + std::to_string(chemicals) + ", not from 1 to " +
                                    std::to_string(max_chemicals));
    if (block_x != 1 && block_x != 4)
        throw std::invalid_argument("block_size_x is " + std::to_string(block_x) + ": figgen runs 1 or 4");
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw std::invalid_argument("the grid is " + std::to_string(width) + " x " + std::to_string(height) +
                                    ", not from 1 x 1 to 16384 x 16384");
    if (depth < 1 || depth > 16384 || static_cast<long long>(width) * height * depth > max_cells)
        throw std::invalid_argument("the grid is " + std::to_string(width) + " x " + std::to_string(height) + " x " +
                                    std::to_string(depth) + ", not from 1 to 16384 a side and at most " +
                                    std::to_string(max_cells) + " cells");
    if (width % block_x != 0)
        throw std::invalid_argument("the grid is " + std::to_string(width) + " cells wide: Ready's blocks of " +
                                    std::to_string(block_x) + " need a multiple of " + std::to_string(block_x));
    for (const auto& [name, value] : parameters) {
        if (!std::isfinite(value))
            throw std::invalid_argument("parameter " + name + " is " + std::to_string(value) + ", not a finite number");
        if (name.empty() || name.size() > 64 || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_'))
            throw std::invalid_argument("parameter name \"" + name + "\" is not a name (letters, digits and _)");
        for (char ch : name)
            if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'))
                throw std::invalid_argument("parameter name \"" + name + "\" is not a name (letters, digits and _)");
    }
    if (edges)
        for (int side = 0; side < 6; ++side) {
            const Edges::Of& of = edges->side[static_cast<std::size_t>(side)];
            const Edges::Of& other = edges->side[static_cast<std::size_t>(side ^ 1)];
            if ((of.edge == Edge::periodic) != (other.edge == Edge::periodic))
                throw std::invalid_argument(std::string("edges: the ") + side_name(side) + " side is " +
                                            edge_name(of.edge) + " and the " + side_name(side ^ 1) + " side " +
                                            edge_name(other.edge) + ": periodic goes on both sides of an axis");
            if (of.edge != Edge::dirichlet) continue;
            if (static_cast<int>(of.value.size()) != chemicals)
                throw std::invalid_argument(std::string("edge_value of the ") + side_name(side) + " side has " +
                                            std::to_string(of.value.size()) + " values, not one a chemical (" +
                                            std::to_string(chemicals) + ")");
            for (double v : of.value)
                if (!std::isfinite(v) || std::abs(v) > 1e30)
                    throw std::invalid_argument(std::string("edge_value of the ") + side_name(side) + " side is " +
                                                std::to_string(v) + ", not a finite number from -1e30 to 1e30");
        }
    for (std::size_t i = 0; i < parameters.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (parameters[i].first == parameters[j].first)
                throw std::invalid_argument("parameter " + parameters[i].first + " is given twice");
}

}  // namespace sim::formula
