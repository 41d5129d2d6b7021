// SPDX-License-Identifier: MIT
// The `emergent` command line: list, help <scene>, run <scene>.
#include <mpi.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/failure_report.hpp"
#include "app/restart_changes.hpp"
#include "app/run.hpp"
#include "app/stop_request.hpp"
#include "emergent/error.hpp"
#include "emergent/plugin.hpp"
#include "emergent/problem.hpp"
#include "io/checkpoint.hpp"
#include "io/h5.hpp"

namespace po = boost::program_options;
using namespace emergent;

namespace {

const char* kUsage =
    "usage: emergent list\n"
    "       emergent help <scene>\n"
    "       emergent run <scene> [--preset P] [--config file.ini]... [--set key=value]...\n"
    "                            [-o DIR [--overwrite]] [--summary-json FILE] [--checkpoint-every N]\n"
    "       emergent run --restart DIR/checkpoint.h5 [--set key=value]... [-o DIR]\n"
    "       emergent --plugin my_scene.so <command> ...   (out-of-tree scenes)\n"
    "-o DIR that holds an earlier run is refused: --overwrite removes that run's files first;\n"
    "--restart DIR/checkpoint.h5 continues it (new files beside the old, nothing replaced).\n"
    "A run with -o DIR stops at the next step on SIGUSR1, SIGTERM or Ctrl-C, writes\n"
    "DIR/checkpoint.h5 and says how to continue it.\n"
    "Exit status: 0 done; 2 bad input; 3 a run-time fault; 4 an I/O failure; 5 stopped on request.\n";

const ProblemInfo& find_scene(const std::string& name) {
    const ProblemInfo* info = ProblemRegistry::instance().find(name);
    if (!info) throw InputError("unknown scene '" + name + "' (see: emergent list)");
    return *info;
}

void list_scenes(std::ostream& out) {
    for (const ProblemInfo* p : ProblemRegistry::instance().all())
        out << p->name << "  " << p->description << "\n";
}

void help_scene(const ProblemInfo& info, std::ostream& out) {
    out << info.name << ": " << info.description << "\n\nparameters (name, default, unit, range):\n";
    for (const auto& p : info.schema.params()) {
        out << "  " << p.name << " = " << p.default_value;
        if (!p.unit.empty()) out << "  [" << p.unit << "]";
        const std::string range = p.range_text();
        if (!range.empty()) out << "  (" << range << ")";
        out << "\n      " << p.help << "\n";
    }
    out << "\npresets:\n";
    for (const auto& [name, values] : info.presets) {
        out << "  " << name << ":";
        for (const auto& [k, v] : values) out << " " << k << "=" << v;
        out << "\n";
    }
}

int run_command(const std::vector<std::string>& args, MPI_Comm comm) {
    po::options_description options("run options");
    options.add_options()("preset", po::value<std::string>()->default_value(""), "preset")(
        "config", po::value<std::vector<std::string>>()->composing(), "INI file")(
        "set", po::value<std::vector<std::string>>()->composing(), "key=value")(
        "output,o", po::value<std::string>()->default_value(""), "output directory")(
        "overwrite", po::bool_switch(), "replace an earlier run in the output directory")(
        "summary-json", po::value<std::string>()->default_value(""), "summary file")(
        "restart", po::value<std::string>()->default_value(""), "checkpoint to continue")(
        "checkpoint-every", po::value<long long>(), "steps between checkpoints")(
        "scene", po::value<std::string>(), "scene");
    po::positional_options_description positional;
    positional.add("scene", 1);
    po::variables_map vm;
    po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
    po::notify(vm);
    auto list = [&](const char* key) {
        return vm.count(key) ? vm[key].as<std::vector<std::string>>() : std::vector<std::string>{};
    };
    std::vector<std::string> sets = list("set");
    // An option given with an empty value is a mistake, not the option left out.
    const std::pair<const char*, const char*> named[] = {
        {"preset", "--preset"}, {"output", "-o"}, {"summary-json", "--summary-json"}, {"restart", "--restart"}};
    for (const auto& [key, flag] : named)
        if (!vm[key].defaulted() && vm[key].as<std::string>().empty())
            throw InputError(std::string(flag) + ": the value is empty");
    io::CheckpointHeader checkpoint;
    app::RunRequest req;
    req.restart_file = vm["restart"].as<std::string>();
    req.output_dir = vm["output"].as<std::string>();
    req.overwrite = vm["overwrite"].as<bool>();
    if (req.overwrite && req.output_dir.empty() && req.restart_file.empty())
        throw InputError("--overwrite: no output directory given (-o DIR)");
    req.summary_json = vm["summary-json"].as<std::string>();
    namespace fs = std::filesystem;
    if (!req.summary_json.empty() && fs::is_directory(req.summary_json))
        throw InputError("--summary-json: '" + req.summary_json + "' is a directory, not a file name");
    if (!req.restart_file.empty() && fs::exists(req.restart_file) && !fs::is_regular_file(req.restart_file))
        throw InputError("--restart: '" + req.restart_file + "' is not a file (give the checkpoint.h5 itself)");
    std::string scene = vm.count("scene") ? vm["scene"].as<std::string>() : "";
    if (!req.restart_file.empty()) {
        checkpoint = io::read_checkpoint_header(req.restart_file, comm);
        if (!scene.empty() && scene != checkpoint.scene)
            throw InputError("--restart: '" + req.restart_file + "' is a checkpoint of scene '" +
                             checkpoint.scene + "', not '" + scene + "'");
        if (!vm["preset"].as<std::string>().empty())
            throw InputError("--restart: a continued run takes its parameters from the "
                             "checkpoint; --preset cannot be combined with it");
        scene = checkpoint.scene;
        req.restart = &checkpoint;
        // Without -o, a continued run writes beside its checkpoint (the run it continues).
        if (req.output_dir.empty())
            req.output_dir = std::filesystem::path(req.restart_file).parent_path().string();
        if (req.output_dir.empty()) req.output_dir = ".";
    }
    if (scene.empty()) throw InputError("run: no scene given (see: emergent list)");
    req.problem = &find_scene(scene);
    if (req.restart) app::add_earlier_values(*req.problem, checkpoint.config);
    if (vm.count("checkpoint-every"))
        sets.push_back("checkpoint_every=" + std::to_string(vm["checkpoint-every"].as<long long>()));
    // A continued run starts from the checkpoint's parameters; --config and --set change them.
    req.config = resolve_config(*req.problem, vm["preset"].as<std::string>(), list("config"), sets,
                                checkpoint.config);
    if (req.restart) {
        const long long end = req.config.integer("equilibration_steps") + req.config.integer("steps");
        if (end < checkpoint.step)
            throw InputError("--restart: the run would end at step " + std::to_string(end) +
                             " (equilibration_steps + steps), before the checkpoint's step " +
                             std::to_string(checkpoint.step) + ": raise steps");
        const std::string changes = app::restart_changes(*req.problem, checkpoint.config, req.config);
        int rank = 0;
        MPI_Comm_rank(comm, &rank);
        if (rank == 0 && !changes.empty()) std::printf("emergent: %s\n", changes.c_str());
    }
    app::run_problem(req, comm);
    return 0;
}

int dispatch(int argc, char** argv, MPI_Comm comm, int rank) {
    // --plugin PATH may appear anywhere; plugins load before the command runs.
    std::vector<std::string> words;
    for (int k = 1; k < argc; ++k) {
        const std::string word = argv[k];
        if (word == "--plugin") {
            if (k + 1 >= argc) throw InputError("--plugin needs a path to a shared library");
            load_plugin(argv[++k]);
        } else {
            words.push_back(word);
        }
    }
    if (words.empty()) throw InputError(std::string("no command given\n") + kUsage);
    const std::string command = words.front();
    std::vector<std::string> args(words.begin() + 1, words.end());
    if (command == "list") {
        if (!args.empty()) throw InputError("list takes no arguments, got '" + args[0] + "'");
        if (rank == 0) list_scenes(std::cout);
        return 0;
    }
    if (command == "help" || command == "--help" || command == "-h") {
        if (args.size() > 1) throw InputError("help takes one scene, got also '" + args[1] + "'");
        if (args.empty()) {
            if (rank == 0) std::cout << kUsage;
        } else if (rank == 0) {
            help_scene(find_scene(args[0]), std::cout);
        }
        return 0;
    }
    if (command == "run") return run_command(args, comm);
    throw InputError("unknown command '" + command + "'");
}

}  // namespace

int main(int argc, char** argv) {
    // Open MPI's ROMIO returns a failed write as an error with the system's reason (errno
    // intact: "No space left on device"); its default OMPIO prints its own lines instead.
    // A choice made in the environment (OMPI_MCA_io) stands.
    setenv("OMPI_MCA_io", "romio321", 0);
    // A run alone (no mpirun) starts Open MPI's daemon itself, and hwloc's GL plugin in both
    // connects to X displays :0-:9 looking for GPUs: slow, and fatal ("X connection to :0
    // broken") when such a server goes away meanwhile. The engine finds its devices through CUDA.
    setenv("HWLOC_COMPONENTS", "-gl", 0);
    MPI_Init(&argc, &argv);
    io::silence_h5_error_stack();
    // Failures meet on a communicator of their own (app/failure_report.hpp).
    MPI_Comm errors;
    MPI_Comm_dup(MPI_COMM_WORLD, &errors);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    int code = exit_code::ok;
    std::string line;
    bool rank_local = false;
    try {
        code = dispatch(argc, argv, MPI_COMM_WORLD, rank);
    } catch (const RuntimeFault& e) {
        // Seen by this rank only: the others may be waiting in a collective, so abort them.
        line = "emergent: error on rank " + std::to_string(rank) + ": " + e.what() + " [" +
               e.where() + "]";
        code = exit_code::run_fault;
        rank_local = true;
    } catch (const InstabilityError& e) {
        line = std::string("emergent: run stopped: ") + e.what();
        code = exit_code::run_fault;
    } catch (const po::error& e) {
        line = std::string("emergent: error: ") + e.what();
        code = exit_code::bad_input;
    } catch (const InputError& e) {
        line = std::string("emergent: error: ") + e.what();
        code = exit_code::bad_input;
    } catch (const IoError& e) {
        line = std::string("emergent: I/O error: ") + e.what();
        code = exit_code::io_failure;
    } catch (const app::RunStopped& e) {
        line = std::string("emergent: ") + e.what();
        code = exit_code::stopped;
    } catch (const std::bad_alloc&) {
        line = "emergent: out of memory (lower the particle count or use more ranks or nodes)";
        code = exit_code::run_fault;
    } catch (const std::exception& e) {
        line = std::string("emergent: internal error: ") + e.what();
        code = exit_code::run_fault;
    } catch (...) {
        line = "emergent: internal error: unknown exception";
        code = exit_code::run_fault;
    }
    if (code != exit_code::ok) code = app::report_failure(errors, code, line, rank_local);
    // A file HDF5 failed to close (a full disk) would crash HDF5's shutdown inside
    // MPI_Finalize: the failure is reported, whatever was closed is whole, so end here.
    if (io::h5_file_close_failed()) {
        if (code == exit_code::ok) {
            std::fprintf(stderr, "emergent: I/O error: an output file could not be closed\n");
            code = exit_code::io_failure;
        }
        std::fflush(nullptr);
        std::_Exit(code);
    }
    MPI_Finalize();
    return code;
}
