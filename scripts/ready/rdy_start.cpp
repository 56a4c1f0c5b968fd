// rdy_start: load a Ready pattern exactly as `rdy` does (SystemFactory::CreateFromFile, which
// applies the initial pattern generator if apply_when_loading="true", then Update(0)) and save
// it immediately with SaveFile(..., generate_initial_pattern_when_loading=false), i.e. the
// START arrays with apply_when_loading="false". Needed because `rdy -n 0 -o X` saves nothing
// (src/cmd/main.cpp only saves inside `if (numiter > 0)`).
//
// Fix-up: AbstractRD::GetAsXML writes <param> values with std::to_string(float) ("%f", 6 decimals),
// which changes parameters such as 0.70710677 -> 0.707107 (so the reloaded rule differs). After
// saving, the <param> values inside <RD> are rewritten with %.9g (exact float round trip), and the
// file is re-loaded to check that all parameters, the formula and the kernel text are unchanged.
#include <AbstractRD.hpp>
#include <OpenCL_utils.hpp>
#include <Properties.hpp>
#include <scene_items.hpp>
#include <SystemFactory.hpp>
#include <vtkObject.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>
using namespace std;

static unique_ptr<AbstractRD> load(const char* f, bool ocl, int platform, int device, Properties& rs)
{
    bool warn_to_update = false;
    return SystemFactory::CreateFromFile(f, ocl, platform, device, rs, warn_to_update);
}

static void fix_params(const char* filename, const AbstractRD& sys)
{
    ifstream in(filename, ios::binary);
    stringstream ss; ss << in.rdbuf(); in.close();
    string s = ss.str();
    const size_t b = s.find("<RD "), e = s.find("</RD>");
    if (b == string::npos || e == string::npos) throw runtime_error("no <RD> element in saved file");
    string rd = s.substr(b, e - b);
    for (int i = 0; i < sys.GetNumberOfParameters(); i++) {
        const string name = sys.GetParameterName(i);
        char val[64]; snprintf(val, sizeof val, "%.9g", (double)sys.GetParameterValue(i));
        const regex re("(<param name=\"" + regex_replace(name, regex(R"([\\^$.|?*+()\[\]{}])"), R"(\$&)") + "\">)[^<]*(</param>)");
        smatch m;
        if (!regex_search(rd, m, re)) throw runtime_error("param not found in saved file: " + name);
        // splice by hand (a format string "$1" + "0.25" would be read as group $10)
        rd = m.prefix().str() + m[1].str() + val + m[2].str() + m.suffix().str();
    }
    s = s.substr(0, b) + rd + s.substr(e);
    ofstream out(filename, ios::binary | ios::trunc); out << s;
    if (!out) throw runtime_error("rewriting saved file failed");
}

int main(int argc, char* argv[])
{
    vtkObject::GlobalWarningDisplayOff();
    if (argc < 3) { cerr << "usage: rdy_start IN.vti OUT.vti [opencl_platform opencl_device]\n"; return 2; }
    const int platform = argc > 3 ? atoi(argv[3]) : 0;
    const int device = argc > 4 ? atoi(argv[4]) : 0;
    if (!ifstream(argv[1])) { cerr << "File does not exist: " << argv[1] << "\n"; return 1; }
    const bool ocl = OpenCL_utils::IsOpenCLAvailable();
    try {
        Properties render_settings("render_settings");
        SetDefaultRenderSettings(render_settings);
        unique_ptr<AbstractRD> system = load(argv[1], ocl, platform, device, render_settings);
        system->Update(0);   // same as rdy: compiles the kernel, uploads + reads back the buffers
        system->SaveFile(argv[2], render_settings, false);
        fix_params(argv[2], *system);

        // self-check: the saved file must describe the same rule
        Properties rs2("render_settings");
        SetDefaultRenderSettings(rs2);
        unique_ptr<AbstractRD> re = load(argv[2], ocl, platform, device, rs2);
        if (re->GetNumberOfParameters() != system->GetNumberOfParameters()) throw runtime_error("check: parameter count differs");
        for (int i = 0; i < system->GetNumberOfParameters(); i++) {
            float a = system->GetParameterValue(i), c = re->GetParameterValue(i);
            if (re->GetParameterName(i) != system->GetParameterName(i) || memcmp(&a, &c, sizeof a))
                throw runtime_error("check: parameter differs after reload: " + system->GetParameterName(i));
        }
        if (re->GetFormula() != system->GetFormula()) throw runtime_error("check: formula differs after reload");
        if (re->GetKernel() != system->GetKernel()) throw runtime_error("check: kernel differs after reload");
        cout << "Saved start state (timesteps_taken=" << system->GetTimestepsTaken() << ", "
             << system->GetNumberOfParameters() << " params written with %.9g; reload check ok) to " << argv[2] << "\n";
    } catch (const exception& e) {
        cerr << "Error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
