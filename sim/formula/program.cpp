#include "sim/formula/program.hpp"

namespace sim::formula {

std::vector<int> sources(const Program& program, const Instr& in) {
    std::vector<int> read;
    auto stencil = [&](int index) {
        for (const StencilSum::Term& t : program.stencils[static_cast<std::size_t>(index)].terms)
            read.insert(read.end(), t.inputs.begin(), t.inputs.end());
    };
    if (in.op == Op::stencil) {
        stencil(in.a);
    } else if (in.op == Op::chain) {
        for (const Chain::Step& st : program.chains[static_cast<std::size_t>(in.a)].steps) {
            if (st.kind == Chain::Kind::stencil) stencil(st.stencil);
            for (int r : {st.x, st.y})
                if (r >= 0) read.push_back(r);
        }
    } else {
        for (int r : {in.a, in.b, in.c, in.mask})
            if (r >= 0) read.push_back(r);
    }
    return read;
}

}  // namespace sim::formula
