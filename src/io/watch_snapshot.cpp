// SPDX-License-Identifier: MIT
// The watch snapshot: a whole new file each time, renamed over the last.
#include "io/watch_snapshot.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

#include "emergent/error.hpp"
#include "io/field_writer.hpp"
#include "io/h5.hpp"

namespace emergent::io {

void WatchSnapshot::Series::add(long long s, double t, const std::vector<double>& v) {
    if (width == 0) width = v.size();
    if (v.size() != width) return;  // a measure whose length changed: its history keeps the first
    if (seen++ % stride != 0) return;
    step.push_back(s);
    time.push_back(t);
    value.insert(value.end(), v.begin(), v.end());
    if (step.size() < kMaxPoints) return;
    for (std::size_t k = 0; 2 * k < step.size(); ++k) {
        step[k] = step[2 * k];
        time[k] = time[2 * k];
        std::copy_n(value.begin() + 2 * k * width, width, value.begin() + k * width);
    }
    const std::size_t kept = (step.size() + 1) / 2;
    step.resize(kept);
    time.resize(kept);
    value.resize(kept * width);
    stride *= 2;
}

WatchSnapshot::WatchSnapshot(std::string dir, std::string scene, std::vector<FieldGrid> grids,
                             double seconds)
    : dir_(std::move(dir)), scene_(std::move(scene)), grids_(std::move(grids)),
      frames_(grids_.size()), have_frame_(grids_.size(), false), seconds_(seconds) {}

void WatchSnapshot::on_fields(std::size_t grid, const FieldFrame& frame) {
    if (!active()) return;
    frames_.at(grid) = frame;
    have_frame_[grid] = true;
    changed_ = true;
}

void WatchSnapshot::on_measures(long long step, double time, const Measures& measures) {
    if (!active()) return;
    for (const auto& [name, value] : measures) {
        latest_[name] = value;
        if (!value.empty() && value.size() <= kMaxHistoryWidth) history_[name].add(step, time, value);
    }
    changed_ = true;
}

void WatchSnapshot::maybe_write(long long step, double time, bool final) {
    if (!active() || !(changed_ || final)) return;
    const auto now = std::chrono::steady_clock::now();
    if (!final && written_ && std::chrono::duration<double>(now - last_write_).count() < seconds_)
        return;
    write(step, time, final);
    last_write_ = now;
    written_ = true;
    changed_ = false;
}

namespace {
// A whole dataset at once, in a file of this rank's own (no MPI-IO).
void write_whole(hid_t parent, const std::string& name, hid_t type, const std::vector<hsize_t>& shape,
                 const void* data) {
    H5Id space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr));
    H5Id set(h5_check(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      "snapshot dataset " + name));
    hsize_t elements = 1;
    for (hsize_t d : shape) elements *= d;
    if (elements > 0)
        h5_check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "snapshot dataset " + name);
}
void write_doubles(hid_t parent, const std::string& name, const std::vector<hsize_t>& shape,
                   const double* data) {
    write_whole(parent, name, H5T_NATIVE_DOUBLE, shape, data);
}
}  // namespace

void WatchSnapshot::write(long long step, double time, bool final) const {
    const std::string path = dir_ + "/snapshot.h5", tmp = path + ".tmp";
    H5Id file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
    if (file < 0) throw IoError("cannot create '" + tmp + "'" + (system_cause().empty() ? "" : ": " + system_cause()));
    try {
        write_contents(file, step, time, final);
        file.close_file(tmp);
    } catch (const IoError& e) {
        discard_file(file, tmp, true);
        throw IoError("cannot write '" + tmp + "': " + e.what());
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw IoError("cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(errno));
}

void WatchSnapshot::write_contents(hid_t file, long long step, double time, bool final) const {
    {
        write_attribute(file, "scene", scene_);
        write_attribute(file, "step", step);
        write_attribute(file, "time", time);
        write_attribute(file, "final", static_cast<long long>(final ? 1 : 0));
        H5Id fields = create_group(file, "fields");
        for (std::size_t g = 0; g < grids_.size(); ++g) {
            if (!have_frame_[g]) continue;
            const FieldGrid& grid = grids_[g];
            H5Id group = create_group(fields, grid.name);
            write_grid_attributes(group, grid);
            const std::vector<hsize_t> cells = {hsize_t(grid.n.z), hsize_t(grid.n.y), hsize_t(grid.n.x)};
            const FieldFrame& f = frames_[g];
            write_doubles(group, "density", cells, f.density.data());
            write_doubles(group, "velocity", {cells[0], cells[1], cells[2], 3}, f.velocity.data());
            write_doubles(group, "temperature", cells, f.temperature.data());
            write_doubles(group, "count", cells, f.count.data());
        }
        H5Id measures = create_group(file, "measures");
        for (const auto& [name, s] : history_) {
            H5Id group = create_group(measures, name);
            const std::vector<hsize_t> n = {s.step.size()};
            write_whole(group, "step", H5T_NATIVE_LLONG, n, s.step.data());
            write_doubles(group, "time", n, s.time.data());
            if (s.width == 1)
                write_doubles(group, "value", n, s.value.data());
            else
                write_doubles(group, "value", {n[0], hsize_t(s.width)}, s.value.data());
        }
        H5Id latest = create_group(file, "latest");
        for (const auto& [name, v] : latest_) write_doubles(latest, name, {v.size()}, v.data());
    }
}

}  // namespace emergent::io
