// Kernel rules against Ready and against what is known.
//
// Ready's numbers: from Ready's own state after one step (rdy -i P -n 1 -o
// start), ten more steps by figgen and by rdy (pocl 3.1 on this machine's
// CPU, scripts/ready/) are the same bits: Conway's Life as an image kernel,
// Goucher's glider as a kernel on a Penrose tiling's mesh.
//
// Known methods: Tim Hutton's advection kernels (Ready's
// Experiments/TimHutton/NumericalMethods) integrate da/dt = -da/dx with
// centred differences by forward Euler, Heun's method and RK4. On a
// Fourier mode the centred differences' semi-discrete solution is known
// exactly (a_i(t) = sin(kappa x_i - omega t), omega = sin(kappa dx) / dx),
// so the error left is the integrator's alone, and halving the kernel's
// timestep divides it by 2, 4 and 16.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "description/stored_mesh.hpp"
#include "description/stored_start.hpp"
#include "ready/pattern.hpp"
#include "sim/kernel/run.hpp"
#include "sim/mesh/mesh.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path here = fs::path(__FILE__).parent_path() / "ready";

std::string kernel_of(const ready::Pattern& p) {
    const auto text = p.description["params"]["kernel"].value<std::string>();
    REQUIRE(text);
    return *text;
}

sim::mesh::Mesh mesh_of(const description::StoredMesh& s) {
    sim::mesh::Mesh m;
    m.points = s.points;
    m.offsets = s.offsets;
    m.point_ids = s.point_ids;
    m.types = s.types;
    m.faces = s.faces;
    m.face_offsets = s.face_offsets;
    return m;
}

}  // namespace

TEST_CASE("Conway's Life as Ready's image kernel: ten steps the same bits as rdy's", "[kernel][ready]") {
    const ready::Pattern start = ready::read_pattern(here / "conway-start.vti", {std::nullopt, true});
    const ready::Pattern after = ready::read_pattern(here / "conway-ready10.vti", {std::nullopt, true});
    REQUIRE(start.start);
    REQUIRE(after.start);
    const description::StoredStart& s = *start.start;
    sim::kernel::ImageRule rule;
    rule.text = kernel_of(start);
    rule.chemicals = s.chemical_count;
    rule.float64 = s.float64;
    std::vector<sim::Grid<double>> grids;
    for (const auto& c : s.chemicals) {
        sim::Grid<double> g(s.height * s.depth, s.width);
        std::copy(c.begin(), c.end(), g.data());
        grids.push_back(g);
    }
    sim::kernel::ImageRun run(rule, s.width, s.height, s.depth, grids);
    run.step(10, 2);
    for (int c = 0; c < s.chemical_count; ++c) {
        const auto& want = after.start->chemicals[static_cast<std::size_t>(c)];
        const sim::Grid<double> got = run.chemical(c);
        CHECK(std::equal(want.begin(), want.end(), got.data()));
    }
    CHECK(after.start->chemicals != s.chemicals);  // ten steps changed something
}

TEST_CASE("Goucher's glider on a Penrose tiling: ten steps the same bits as rdy's", "[kernel][ready][mesh]") {
    const ready::Pattern start = ready::read_pattern(here / "goucher-start.vtu");
    const ready::Pattern after = ready::read_pattern(here / "goucher-ready10.vtu");
    REQUIRE(start.mesh);
    REQUIRE(after.mesh);
    const sim::mesh::Mesh mesh = mesh_of(*start.mesh);
    const sim::mesh::Neighbours n = sim::mesh::neighbours(mesh, sim::mesh::Kind::vertex);
    CHECK(n.max_neighbors == 11);
    sim::kernel::MeshRule rule;
    rule.text = kernel_of(start);
    rule.chemicals = 1;
    sim::kernel::MeshRun run(rule, static_cast<long long>(mesh.cell_count()), n.max_neighbors, n.indices, n.weights,
                             start.mesh->chemicals);
    run.step(10, 2);
    CHECK(run.chemical(0) == after.mesh->chemicals[0]);
    CHECK(after.mesh->chemicals[0] != start.mesh->chemicals[0]);
}

TEST_CASE("Tim Hutton's advection kernels show their textbook orders: Euler 1, Heun 2, RK4 4", "[kernel]") {
    const double dx = 0.1, t_end = 1.6;
    const int cells = 256;
    const double kappa = 2 * M_PI * 4 / (cells * dx);  // four waves round the ring
    const double omega = std::sin(kappa * dx) / dx;    // the centred differences' phase speed
    struct Method {
        const char* file;
        double order;
    };
    for (const Method& m : {Method{"advection_forwardEuler_double.vti", 1}, Method{"advection_HeunsMethod_double.vti", 2},
                            Method{"advection_RungeKutta4_double.vti", 4}}) {
        const std::string text = kernel_of(ready::read_pattern(here / m.file));
        const std::string said = "double dt = 0.05;";
        REQUIRE(text.find(said) != std::string::npos);
        REQUIRE(text.find("double dx = 0.1;") != std::string::npos);
        std::vector<double> errors;
        for (double dt : {0.05, 0.025, 0.0125}) {
            std::string k = text;
            char value[64];
            std::snprintf(value, sizeof value, "double dt = %.17g;", dt);
            k.replace(k.find(said), said.size(), value);
            sim::kernel::ImageRule rule;
            rule.text = k;
            rule.float64 = true;
            sim::Grid<double> a(1, cells);
            for (int i = 0; i < cells; ++i) a(0, i) = std::sin(kappa * i * dx);
            sim::kernel::ImageRun run(rule, cells, 1, 1, {a});
            const int steps = static_cast<int>(std::lround(t_end / dt));
            run.step(steps, 1);
            const sim::Grid<double> got = run.chemical(0);
            double worst = 0;
            for (int i = 0; i < cells; ++i) worst = std::max(worst, std::fabs(got(0, i) - std::sin(kappa * i * dx - omega * t_end)));
            errors.push_back(worst);
        }
        for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
            const double order = std::log2(errors[k] / errors[k + 1]);
            INFO(m.file << ": errors " << errors[k] << " then " << errors[k + 1] << ", order " << order);
            CHECK(order == Approx(m.order).margin(0.15));
        }
    }
}
