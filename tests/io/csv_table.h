// tests/io/csv_table.h: a CSV file of a run read as pandas.read_csv(f, comment='#') reads it:
// lines that start with '#' skipped (the first one kept as `comment`), the first other line the
// header, fields split at commas outside double quotes (RFC 4180: "" inside quotes is a quote),
// empty fields kept empty (pandas: NaN in a numeric column).
#pragma once

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <string_view>
#include <vector>

namespace frontier::test
{

inline std::vector<std::string> splitCsvLine(std::string_view line)
{
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i)
    {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        {
            fields.back() += '"';
            ++i;
        }
        else if (c == '"')
        {
            quoted = !quoted;
        }
        else if (c == ',' && !quoted)
        {
            fields.emplace_back();
        }
        else
        {
            fields.back() += c;
        }
    }
    return fields;
}

struct CsvTable
{
    std::string comment; // the first '#' line
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;

    // Index of a column; a test failure (and -1) when there is none.
    int column(const std::string& name) const
    {
        for (std::size_t i = 0; i < columns.size(); ++i)
        {
            if (columns[i] == name)
            {
                return static_cast<int>(i);
            }
        }
        ADD_FAILURE() << "no column '" << name << "'";
        return -1;
    }
    const std::string& text(std::size_t row, const std::string& name) const
    {
        return rows.at(row).at(static_cast<std::size_t>(column(name)));
    }
    // The field as a number; NaN when it is empty (as pandas reads it).
    double number(std::size_t row, const std::string& name) const
    {
        const std::string& field = text(row, name);
        return field.empty() ? std::nan("") : std::stod(field);
    }
};

inline CsvTable readCsvTable(const std::string& path)
{
    CsvTable table;
    std::ifstream in(path);
    std::string line;
    bool header = false;
    while (std::getline(in, line))
    {
        if (!line.empty() && line.front() == '#')
        {
            table.comment = table.comment.empty() ? line : table.comment;
            continue;
        }
        if (!header)
        {
            table.columns = splitCsvLine(line);
            header = true;
            continue;
        }
        table.rows.push_back(splitCsvLine(line));
    }
    return table;
}

} // namespace frontier::test
