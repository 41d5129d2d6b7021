// SPDX-License-Identifier: MIT
// Half Verlet list from a cell list.
#include "neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "emergent/error.hpp"
#include "emergent/execution.hpp"

namespace emergent {

void NeighbourList::set_pair_ranges(const std::vector<double>& range, int n_species) {
    if (n_species < 0 || range.size() != std::size_t(n_species) * std::size_t(n_species))
        throw std::logic_error("NeighbourList::set_pair_ranges: the table is not n x n");
    const std::size_t n = std::size_t(n_species);
    n_range_species_ = n_species;
    range_table_.assign(n * n + n, 0.0);
    for (std::size_t k = 0; k < n * n; ++k) {
        const double r = range[k] > 0 ? range[k] + skin_ : 0.0;
        range_table_[k] = r > 0 ? r * r : -1.0;
        range_table_[n * n + k / n] = std::max(range_table_[n * n + k / n], r);
    }
}

/// Whether every particle's species (owned and ghost) has its row in the table: only then may
/// a search from a particle stop at its species' longest range (a pair with an undescribed
/// species is listed within the whole range, from either member).
static bool species_described(const ParticleStore& store, int n_species) {
    return std::all_of(store.species.begin(), store.species.begin() + std::ptrdiff_t(store.size()),
                       [&](int s) { return s >= 0 && s < n_species; });
}

// A squared range for the search on the cells' single-precision copy: widened by the copy's
// rounding and rounded up, so that no pair in range is missed.
static float binned_limit(double range, const CellList& cells) {
    const double r = range + cells.binned_distance_error();
    return std::nextafter(static_cast<float>(r * r), 1e30f);
}

std::vector<float> NeighbourList::binned_pair_limits(const CellList& cells) const {
    const std::size_t n = std::size_t(n_range_species_);
    std::vector<float> limit(n * n, -1.0f);
    for (std::size_t k = 0; k < limit.size(); ++k)
        if (range_table_[k] > 0) limit[k] = binned_limit(std::sqrt(range_table_[k]), cells);
    return limit;
}

std::vector<Int3> NeighbourList::species_reach(const ParticleStore& store, const CellIndex& grid) const {
    const unsigned n = static_cast<unsigned>(n_range_species_);
    std::vector<Int3> reach(n, grid.reach);
    if (n && species_described(store, n_range_species_))
        for (unsigned s = 0; s < n; ++s) reach[s] = grid.reach_of(range_table_[n * n + s]);
    return reach;
}

void NeighbourList::build_full(const ParticleStore& store, const CellList& cells) {
    build_general(store, cells, true);
}

void NeighbourList::build_general(const ParticleStore& store, const CellList& cells, bool full) {
    const std::size_t n_owned = store.n_owned();
    const double r2max = list_cutoff() * list_cutoff();
    const Vec3* x = store.position.data();
    const std::int64_t* body = store.has_rigid_fields() ? store.body.data() : nullptr;
    const unsigned n_species = static_cast<unsigned>(n_range_species_);
    const int* species = n_species ? store.species.data() : nullptr;
    const double* pair_range_sq = range_table_.data();
    offset_.assign(n_owned + 1, 0);
    neighbour_.clear();
    const CellIndex& grid = cells.index();
    // The reach of a search from each species (or the grid's, for all).
    const std::vector<Int3> reach = species_reach(store, grid);
    for (std::size_t i = 0; i < n_owned; ++i) {
        const unsigned si = species ? static_cast<unsigned>(species[i]) : 0;
        auto consider = [&](std::uint32_t j) {
            if (full ? j == i : j <= i) return;
            if (body && body[i] >= 0 && body[i] == body[j]) return;  // same body
            const Vec3 r = x[i] - x[j];
            double limit = r2max;
            if (species) {
                const unsigned sj = static_cast<unsigned>(species[j]);
                if (si < n_species && sj < n_species) limit = pair_range_sq[si * n_species + sj];
            }
            if (dot(r, r) < limit) neighbour_.push_back(j);
        };
        grid.visit_within(x[i], si < n_species ? reach[si] : grid.reach, cells.starts(), cells.members(), consider);
        offset_[i + 1] = static_cast<std::uint32_t>(neighbour_.size());
    }
    n_pairs_ = neighbour_.size();
    keep_reference(store, n_owned);
}

// The positions the list was built at. When the owned count outgrows the copy (particles
// migrating in), the old copy is freed before the new one is made: assign() would hold both, and
// on 2 ranks that transient (24 B per owned particle) set the run's peak memory.
void NeighbourList::keep_reference(const ParticleStore& store, std::size_t n_owned) {
    if (n_owned > built_at_.capacity()) {
        std::vector<Vec3>().swap(built_at_);
        built_at_.reserve(n_owned + n_owned / 32);
    }
    built_at_.assign(store.position.begin(), store.position.begin() + n_owned);
}

// Half list where cells may hold owned particles and ghosts together (rigid bodies' constituents
// outside the domain, their ghosts inside it). A cell's members are in ascending index, so its
// owned members come first and its ghosts after them. An owned pair is listed under its member in
// the earlier slot (cells in index order): from a particle, later slots of its own cell, whole
// cells after it and only the ghosts of cells before it. An owned-ghost pair is listed under its
// owned member, as everywhere. Rows hold their pairs in the order of the general search, so with
// owned particles in cell order (the engine's) a row lists what that search lists under i < j,
// in the same order, plus at most a few pairs just beyond their range (a zero force).
void NeighbourList::build_general_half(const ParticleStore& store, const CellList& cells) {
    const std::size_t n_owned = store.n_owned();
    const std::uint32_t* member = cells.members();
    const int n_cells = cells.n_cells();
    place_.assign(n_owned, Place{0, -1});
    first_ghost_.resize(std::size_t(n_cells));
    for (int c = 0; c < n_cells; ++c) {
        std::uint32_t a = cells.first(c);
        for (const std::uint32_t e = cells.first(c + 1); a < e && member[a] < n_owned; ++a) place_[member[a]] = Place{a, c};
        first_ghost_[std::size_t(c)] = a;
    }
    if (n_range_species_ > 1 && species_described(store, n_range_species_) &&
        double(n_range_species_) * double(n_cells) <= 64.0 * double(cells.first(n_cells)) + 4096.0) {
        build_half_by_species(store, cells);
        return;
    }
    offset_.assign(n_owned + 1, 0);
    const std::int64_t* body = store.has_rigid_fields() ? store.body.data() : nullptr;
    // The search runs on the cells' single-precision copy, its ranges widened by the copy's
    // rounding (as in build()): a pair a little beyond its range may be listed; its force is 0.
    const BinnedPoint* xb = cells.binned_positions();
    const float r2f = binned_limit(list_cutoff(), cells);
    const unsigned n_species = static_cast<unsigned>(n_range_species_);
    const int* species = n_species ? store.species.data() : nullptr;
    const std::vector<float> pair_r2f = binned_pair_limits(cells);
    const CellIndex& grid = cells.index();
    const std::vector<Int3> reach = species_reach(store, grid);
    const Int3 shape = grid.n;
    // Species and body by slot: the candidates' are read in slot order, not gathered by index.
    const std::size_t n_slots = cells.first(n_cells);
    slot_species_.resize(species ? n_slots : 0);
    slot_body_.resize(body ? n_slots : 0);
    for (std::size_t s = 0; s < slot_species_.size(); ++s) slot_species_[s] = species[member[s]];
    for (std::size_t s = 0; s < slot_body_.size(); ++s) slot_body_[s] = body[member[s]];
    const int* species_at = slot_species_.data();
    const std::int64_t* body_at = slot_body_.data();
    // Slot ranges of the cells within reach of one cell (other than the cell itself), in the
    // search's order, collected once for consecutive rows with the same cell and reach.
    std::vector<std::uint32_t> range_begin, range_end;
    std::vector<std::uint8_t> range_after;  // 1: a range of the cell's own
    int ranges_cell = -1;
    Int3 ranges_reach{-1, -1, -1};
    std::uint32_t bound = 0;
    std::size_t count = 0;
    neighbour_.resize(std::max<std::size_t>(neighbour_.size(), n_pairs_ + n_pairs_ / 8 + 1024));
    for (std::size_t i = 0; i < n_owned; ++i) {
        const Place here = place_[i];
        if (here.cell < 0) throw std::logic_error("NeighbourList::build: an owned particle is in no cell");
        const unsigned si = species ? static_cast<unsigned>(species[i]) : 0;
        const Int3 r = si < n_species ? reach[si] : grid.reach;
        const int c = here.cell;
        if (c != ranges_cell || r.x != ranges_reach.x || r.y != ranges_reach.y || r.z != ranges_reach.z) {
            ranges_cell = c;
            ranges_reach = r;
            range_begin.clear();
            range_end.clear();
            range_after.clear();
            bound = 0;
            const int cx = c % shape.x, cy = (c / shape.x) % shape.y, cz = c / (shape.x * shape.y);
            for (int dz = -r.z; dz <= r.z; ++dz)
                for (int dy = -r.y; dy <= r.y; ++dy)
                    for (int dx = -r.x; dx <= r.x; ++dx) {
                        const int ax = cx + dx, ay = cy + dy, az = cz + dz;
                        if (ax < 0 || ay < 0 || az < 0 || ax >= shape.x || ay >= shape.y || az >= shape.z) continue;
                        const int c2 = (az * shape.y + ay) * shape.x + ax;
                        // The cell itself is a marker: its range depends on the row's slot.
                        const std::uint32_t b = c2 == c ? 0 : (c2 < c ? first_ghost_[std::size_t(c2)] : cells.first(c2));
                        const std::uint32_t e = c2 == c ? 0 : cells.first(c2 + 1);
                        if (c2 != c && b == e) continue;
                        if (c2 != c && !range_end.empty() && range_end.back() == b && !range_after.back()) {
                            range_end.back() = e;
                        } else {
                            range_begin.push_back(b);
                            range_end.push_back(e);
                            range_after.push_back(c2 == c ? 1 : 0);
                        }
                        bound += e - b;
                    }
        }
        const std::uint32_t a = here.slot, own_end = cells.first(c + 1);
        if (neighbour_.size() < count + bound + (own_end - a))
            neighbour_.resize(count + bound + (own_end - a) + (count + bound) / 2);
        std::uint32_t* out = neighbour_.data();
        const BinnedPoint xi = xb[a];
        const std::int64_t bi = body ? body[i] : -1;
        // Branch-free append: write every candidate, advance only past those listed.
        for (std::size_t k = 0; k < range_begin.size(); ++k) {
            const std::uint32_t b0 = range_after[k] ? a + 1 : range_begin[k];
            const std::uint32_t e0 = range_after[k] ? own_end : range_end[k];
            for (std::uint32_t s = b0; s < e0; ++s) {
                const float dx = xi.x - xb[s].x, dy = xi.y - xb[s].y, dz = xi.z - xb[s].z;
                float limit = r2f;
                if (species) {
                    const unsigned sj = static_cast<unsigned>(species_at[s]);
                    if (si < n_species && sj < n_species) limit = pair_r2f[si * n_species + sj];
                }
                out[count] = member[s];
                count += (dx * dx + dy * dy + dz * dz < limit && !(bi >= 0 && body_at[s] == bi)) ? 1 : 0;
            }
        }
        offset_[i + 1] = static_cast<std::uint32_t>(count);
    }
    n_pairs_ = count;
    keep_reference(store, n_owned);
}

// The general half list with the candidates binned by species and cell: species by species,
// each species' slots in cell order, so one row of cells along x of one species is one run of
// the copy. A row searches only the species its own meets (a site one partner type among many,
// a sphere no site): in the capsid scene's clusters the plain search tests ~50 candidates per
// pair listed. Which rows list a pair is decided as in build_general_half, by a key per
// candidate: its slot when owned (listed from an earlier slot of its cell, or from an earlier
// cell), the largest key when a ghost (listed from every owned particle). A row lists its pairs
// species by species, then in the plain search's order.
void NeighbourList::build_half_by_species(const ParticleStore& store, const CellList& cells) {
    const std::size_t n_owned = store.n_owned();
    const std::uint32_t* member = cells.members();
    const int n_cells = cells.n_cells();
    const unsigned n_species = static_cast<unsigned>(n_range_species_);
    const std::size_t n_slots = cells.first(n_cells);
    const int* species = store.species.data();
    const std::int64_t* body = store.has_rigid_fields() ? store.body.data() : nullptr;
    const BinnedPoint* xb = cells.binned_positions();
    constexpr std::uint32_t kGhost = 0xffffffffu;

    // Counting sort of the slots by (species, cell), in one table: counts, their exclusive sums
    // (each bucket's start), advanced past each slot placed (each bucket's end), then shifted by
    // one so that entry k is bucket k's start again.
    const std::size_t n_buckets = std::size_t(n_species) * std::size_t(n_cells);
    by_species_first_.assign(n_buckets + 1, 0);
    std::uint32_t* bucket = by_species_first_.data();
    for (int c = 0; c < n_cells; ++c)
        for (std::uint32_t a = cells.first(c); a < cells.first(c + 1); ++a)
            ++bucket[std::size_t(species[member[a]]) * std::size_t(n_cells) + std::size_t(c)];
    std::exclusive_scan(bucket, bucket + n_buckets, bucket, std::uint32_t(0));
    sorted_x_.resize(n_slots);
    sorted_member_.resize(n_slots);
    sorted_key_.resize(n_slots);
    slot_body_.resize(body ? n_slots : 0);
    for (int c = 0; c < n_cells; ++c)
        for (std::uint32_t a = cells.first(c); a < cells.first(c + 1); ++a) {
            const std::uint32_t m = member[a];
            const std::uint32_t t = bucket[std::size_t(species[m]) * std::size_t(n_cells) + std::size_t(c)]++;
            sorted_x_[t] = xb[a];
            sorted_member_[t] = m;
            sorted_key_[t] = m < n_owned ? a : kGhost;
            if (body) slot_body_[t] = body[m];
        }
    std::copy_backward(bucket, bucket + n_buckets, bucket + n_buckets + 1);
    bucket[0] = 0;
    // The species each species meets, and the squared ranges on the single-precision copy.
    const std::vector<float> pair_r2f = binned_pair_limits(cells);
    std::vector<std::vector<unsigned>> meets(n_species);
    for (unsigned a = 0; a < n_species; ++a)
        for (unsigned b = 0; b < n_species; ++b)
            if (pair_r2f[a * n_species + b] > 0) meets[a].push_back(b);
    const CellIndex& grid = cells.index();
    const std::vector<Int3> reach = species_reach(store, grid);
    const Int3 shape = grid.n;

    offset_.assign(n_owned + 1, 0);
    std::size_t count = 0;
    neighbour_.resize(std::max<std::size_t>(neighbour_.size(), n_pairs_ + n_pairs_ / 8 + 1024));
    const BinnedPoint* xs = sorted_x_.data();
    const std::uint32_t* key = sorted_key_.data();
    const std::uint32_t* who = sorted_member_.data();
    const std::int64_t* body_at = slot_body_.data();
    const std::uint32_t* first = by_species_first_.data();
    // Runs of one species' cells along x for one row of the search, and the smallest key a
    // candidate in them must have.
    struct Run {
        std::uint32_t cell_begin, cell_end, min_key;
    };
    // Collected once for consecutive rows in one cell with one reach (rows are in cell order);
    // only the own cell's smallest key changes from row to row.
    std::vector<Run> runs;
    std::size_t own_run = 0;
    int runs_cell = -1;
    Int3 runs_reach{-1, -1, -1};
    for (std::size_t i = 0; i < n_owned; ++i) {
        const Place here = place_[i];
        if (here.cell < 0) throw std::logic_error("NeighbourList::build: an owned particle is in no cell");
        const unsigned si = static_cast<unsigned>(species[i]);
        const Int3 r = reach[si];
        const int c = here.cell;
        if (c != runs_cell || r.x != runs_reach.x || r.y != runs_reach.y || r.z != runs_reach.z) {
            runs_cell = c;
            runs_reach = r;
            runs.clear();
            const int cx = c % shape.x, cy = (c / shape.x) % shape.y, cz = c / (shape.x * shape.y);
            const int x0 = std::max(cx - r.x, 0), x1 = std::min(cx + r.x, shape.x - 1);
            for (int dz = -r.z; dz <= r.z; ++dz)
                for (int dy = -r.y; dy <= r.y; ++dy) {
                    const int ay = cy + dy, az = cz + dz;
                    if (ay < 0 || az < 0 || ay >= shape.y || az >= shape.z) continue;
                    const std::uint32_t row = std::uint32_t((az * shape.y + ay) * shape.x);
                    if (dz != 0 || dy != 0) {  // a whole row before the cell (ghosts only) or after it
                        runs.push_back({row + std::uint32_t(x0), row + std::uint32_t(x1) + 1,
                                        (dz < 0 || (dz == 0 && dy < 0)) ? kGhost : 0u});
                    } else {
                        if (x0 < cx) runs.push_back({row + std::uint32_t(x0), std::uint32_t(c), kGhost});
                        own_run = runs.size();
                        runs.push_back({std::uint32_t(c), std::uint32_t(c) + 1, 0u});
                        if (cx < x1) runs.push_back({std::uint32_t(c) + 1, row + std::uint32_t(x1) + 1, 0u});
                    }
                }
        }
        runs[own_run].min_key = here.slot + 1;  // the own cell: its later slots and its ghosts
        const BinnedPoint own = cells.binned_positions()[here.slot];
        const std::int64_t bi = body ? body[i] : -1;
        for (const unsigned sj : meets[si]) {
            const float limit = pair_r2f[si * n_species + sj];
            const std::size_t base = std::size_t(sj) * std::size_t(n_cells);
            for (const Run& run : runs) {
                const std::uint32_t b0 = first[base + run.cell_begin], e0 = first[base + run.cell_end];
                if (neighbour_.size() < count + (e0 - b0)) neighbour_.resize(count + (e0 - b0) + count / 2 + 1024);
                std::uint32_t* out = neighbour_.data();
                // Branch-free append: write every candidate, advance only past those listed.
                for (std::uint32_t t = b0; t < e0; ++t) {
                    const float dx = own.x - xs[t].x, dy = own.y - xs[t].y, dz = own.z - xs[t].z;
                    out[count] = who[t];
                    count += (dx * dx + dy * dy + dz * dz < limit && key[t] >= run.min_key &&
                              !(bi >= 0 && body_at[t] == bi)) ? 1 : 0;
                }
            }
        }
        offset_[i + 1] = static_cast<std::uint32_t>(count);
    }
    n_pairs_ = count;
    keep_reference(store, n_owned);
}

void NeighbourList::build(const ParticleStore& store, const CellList& cells,
                          bool owned_outside_domain) {
    if (owned_outside_domain) {
        build_general_half(store, cells);
        return;
    }
    const std::size_t n_owned = store.n_owned();
    const Int3 shape = cells.shape();
    const std::uint32_t* member = cells.members();
    // Where each owned particle sits among the cells' members. Rows are written in index
    // order; the search itself is geometric (later inner cells, ghost cells, later slots of
    // the own cell), so a pair is listed once whatever the order of the indices. The engine
    // orders owned particles by cell, or by cell within two parts (interior first, for the
    // halo overlap): consecutive rows then mostly share a cell and its ranges below.
    place_.assign(n_owned, Place{0, -1});
    for (int c = 0; c < cells.n_cells(); ++c) {
        if (!cells.is_inner(c)) continue;
        for (std::uint32_t a = cells.first(c); a < cells.first(c + 1); ++a) {
            if (member[a] >= n_owned)
                throw std::logic_error("NeighbourList::build: a ghost lies inside the domain; "
                                       "this region needs the general search");
            place_[member[a]] = Place{a, c};
        }
    }
    offset_.assign(n_owned + 1, 0);
    // The search runs on the cells' single-precision copy, its range widened by the copy's
    // rounding so that no pair in range is missed (benchmarks/results/host_speed.md, "Peak memory against LAMMPS").
    const BinnedPoint* xb = cells.binned_positions();
    const float r2f = binned_limit(list_cutoff(), cells);
    const unsigned n_species = static_cast<unsigned>(n_range_species_);
    const int* species = n_species ? store.species.data() : nullptr;
    const std::vector<float> pair_r2f = binned_pair_limits(cells);
    // Stencil: the cells within reach as offsets of the linear index, in increasing order, so
    // that neighbouring cells of one row (consecutive indices, consecutive slots) merge into
    // one range below. Inner cells always have all of them: the grid's ghost shell is at least
    // `reach` cells thick.
    const Int3 reach = cells.reach();
    std::vector<int> stencil;
    for (int dz = -reach.z; dz <= reach.z; ++dz)
        for (int dy = -reach.y; dy <= reach.y; ++dy)
            for (int dx = -reach.x; dx <= reach.x; ++dx)
                if (dx || dy || dz) stencil.push_back((dz * shape.y + dy) * shape.x + dx);
    // Away from the ghost shell every stencil cell is inner, so the search is the rows of
    // cells after c, whole (their first cell's offset), and the rest of c's own row.
    std::vector<int> later_rows;
    for (int dz = 0; dz <= reach.z; ++dz)
        for (int dy = dz == 0 ? 1 : -reach.y; dy <= reach.y; ++dy)
            later_rows.push_back((dz * shape.y + dy) * shape.x - reach.x);
    const int row_cells = 2 * reach.x + 1;
    std::vector<std::uint32_t> range_begin(stencil.size() + 1), range_end(stencil.size() + 1);
    // Room for the list in one allocation, made before the search (the old entries are of no
    // use, so they are freed first): growing it while searching holds old and new at once, up
    // to twice the list at the peak. The estimate is the last build's count, or at the first
    // build the pairs of a uniform fluid of this density, 1.3x (an fcc lattice has 1.25x).
    const double pairs_uniform = 0.5 * 4.18879 * std::pow(list_cutoff(), 3) * store.size() / cells.grid_volume();
    const std::size_t expected = n_pairs_ > 0 ? n_pairs_ + n_pairs_ / 8
                                              : static_cast<std::size_t>(1.3 * pairs_uniform * n_owned);
    if (neighbour_.size() < expected + 1024) {
        std::vector<std::uint32_t>().swap(neighbour_);
        neighbour_.resize(expected + 1024);
    }
    std::size_t count = 0;
    int c = -1;  // the cell whose ranges are collected
    std::uint32_t bound = 0;
    int n_ranges = 0;
    for (std::size_t i = 0; i < n_owned; ++i) {
        const Place here = place_[i];
        if (here.cell < 0) throw std::logic_error("NeighbourList::build: an owned particle lies outside the domain");
        if (here.cell != c) {
            // Inner cells before c are searched from their own particles; inner cells after c
            // and ghost cells from c's. Collect the slot ranges once per cell, merging adjacent ones.
            c = here.cell;
            bound = 0;
            n_ranges = 0;
            auto add_range = [&](std::uint32_t b, std::uint32_t e) {
                if (b == e) return;
                bound += e - b;
                if (n_ranges > 0 && range_end[n_ranges - 1] == b)
                    range_end[n_ranges - 1] = e;
                else
                    range_begin[n_ranges] = b, range_end[n_ranges] = e, ++n_ranges;
            };
            if (cells.is_deep(c)) {
                add_range(cells.first(c + 1), cells.first(c + 1 + reach.x));
                for (const int row : later_rows)
                    add_range(cells.first(c + row), cells.first(c + row + row_cells));
            } else {
                for (const int offset : stencil) {
                    const int c2 = c + offset;
                    if (c2 < c && cells.is_inner(c2)) continue;
                    add_range(cells.first(c2), cells.first(c2 + 1));
                }
            }
        }
        const std::uint32_t a = here.slot, own_end = cells.first(c + 1);
        const BinnedPoint xi = xb[a];
        if (neighbour_.size() < count + bound + (own_end - a))
            neighbour_.resize(count + bound + (own_end - a) + (count + bound) / 2);
        std::uint32_t* out = neighbour_.data();
        // Branch-free append: write every candidate, advance only past those in range.
        auto consider = [&](std::uint32_t b) {
            const float dx = xi.x - xb[b].x, dy = xi.y - xb[b].y, dz = xi.z - xb[b].z;
            out[count] = member[b];
            count += (dx * dx + dy * dy + dz * dz < r2f) ? 1 : 0;
        };
        // With ranges by species: the pair's own, widened as the whole range is.
        const unsigned si = species ? static_cast<unsigned>(species[i]) : 0;
        auto consider_by_species = [&](std::uint32_t b) {
            const float dx = xi.x - xb[b].x, dy = xi.y - xb[b].y, dz = xi.z - xb[b].z;
            const std::uint32_t j = member[b];
            const unsigned sj = static_cast<unsigned>(species[j]);
            out[count] = j;
            const float limit = si < n_species && sj < n_species ? pair_r2f[si * n_species + sj] : r2f;
            count += (dx * dx + dy * dy + dz * dz < limit) ? 1 : 0;
        };
        if (species) {
            for (std::uint32_t b = a + 1; b < own_end; ++b) consider_by_species(b);
            for (int r = 0; r < n_ranges; ++r)
                for (std::uint32_t b = range_begin[r]; b < range_end[r]; ++b) consider_by_species(b);
        } else {
            for (std::uint32_t b = a + 1; b < own_end; ++b) consider(b);
            for (int r = 0; r < n_ranges; ++r)
                for (std::uint32_t b = range_begin[r]; b < range_end[r]; ++b) consider(b);
        }
        offset_[i + 1] = static_cast<std::uint32_t>(count);
    }
    n_pairs_ = count;
    keep_reference(store, n_owned);
}

double NeighbourList::max_displacement_sq(const ParticleStore& store) const {
    // A NaN wins the maximum and is reported (exec::transform_max).
    return exec::transform_max(exec::Host{}, built_at_.size(), 0.0,
                               SquaredDisplacement{store.position.data(), built_at_.data()});
}

bool NeighbourList::needs_rebuild(const ParticleStore& store, MPI_Comm comm) const {
    return rebuild_due(max_displacement_sq(store), comm);
}

bool NeighbourList::rebuild_due(double local, MPI_Comm comm) const {
    // NaN is mapped to +inf so the MPI max carries it to every rank.
    if (std::isnan(local)) local = std::numeric_limits<double>::infinity();
    double global = 0;
    exec::count_collective();
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm);
    return rebuild_due(global);
}

bool NeighbourList::rebuild_due(double global) const {
    if (std::isinf(global) || std::isnan(global))
        throw InstabilityError("non-finite particle position: the run went unstable "
                               "(time step too large, overlapping start, or forces too strong)");
    // The list is rebuilt as soon as some particle passes skin/2, so a displacement beyond
    // the whole ghost shell means one step jumped further than any pair range: a blow-up.
    if (global > list_cutoff() * list_cutoff()) {
        std::ostringstream msg;
        msg << "a particle moved " << std::sqrt(global) << " sigma within one step, more than "
            << "cutoff + skin = " << list_cutoff()
            << ": the run went unstable (time step too large or forces too strong)";
        throw InstabilityError(msg.str());
    }
    return global > 0.25 * skin_ * skin_;
}

}  // namespace emergent
