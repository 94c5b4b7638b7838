// io/target_table.h: actuator targets from a CSV file (private to io/).
//
// The file: lines starting with '#' and blank lines are skipped; the first other line is the
// header, comma-separated column names, one of them `time`; then one row of numbers per line, as
// many as the header has names, times strictly increasing (s). pandas writes such files with
// `df.to_csv(f, index=False)`.
#pragma once

#include <string>
#include <vector>

namespace frontier::io::detail
{

struct TargetColumn
{
    std::vector<double> times;  // s, strictly increasing
    std::vector<double> values; // the column's values at those times
    std::vector<int> lines;     // the line of each row in the file (1-based)
};

// The `time` column and the named one; throws InputError naming the file and line of a problem
// (a missing column names the columns there are and the closest one; a column named twice is
// refused).
TargetColumn readTargetColumn(const std::string& path, const std::string& column);

} // namespace frontier::io::detail
