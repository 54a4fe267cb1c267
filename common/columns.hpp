// Tables of records as the columns and flat arrays that NetCDF variables and CSV files
// hold: column<T>(rows, &Row::field) or column<T>(rows, lambda), and nested vectors
// concatenated row-major (last index fastest, as NetCDF stores (a, b, c)).
#pragma once
#include <functional>
#include <vector>

namespace flotsam {

template <class T, class Rows, class F>
std::vector<T> column(const Rows& rows, F f) {
    std::vector<T> out;
    out.reserve(rows.size());
    for (const auto& r : rows) out.push_back(T(std::invoke(f, r)));
    return out;
}

template <class T>
std::vector<T> flatten(const std::vector<std::vector<T>>& a) {
    std::vector<T> out;
    for (const auto& row : a) out.insert(out.end(), row.begin(), row.end());
    return out;
}

template <class T>
std::vector<T> flatten(const std::vector<std::vector<std::vector<T>>>& a) {
    std::vector<T> out;
    for (const auto& block : a) {
        const std::vector<T> rows = flatten(block);
        out.insert(out.end(), rows.begin(), rows.end());
    }
    return out;
}

}  // namespace flotsam
