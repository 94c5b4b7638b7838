// io/target_table.cpp: the time column and one value column of a target CSV file.
#include "io/target_table.h"

#include "io/file_util.h"
#include "io/scene.h"
#include "io/suggest.h"

#include <map>
#include <optional>
#include <sstream>

namespace frontier::io::detail
{

namespace
{
std::string trimmed(const std::string& text)
{
    const std::size_t begin = text.find_first_not_of(" \t\r");
    if (begin == std::string::npos)
    {
        return {};
    }
    const std::size_t end = text.find_last_not_of(" \t\r");
    return text.substr(begin, end - begin + 1);
}

std::vector<std::string> fields(const std::string& line)
{
    std::vector<std::string> out;
    std::stringstream in(line);
    std::string field;
    while (std::getline(in, field, ','))
    {
        out.push_back(trimmed(field));
    }
    if (!line.empty() && line.back() == ',')
    {
        out.emplace_back(); // a trailing comma leaves an empty last field
    }
    return out;
}

// A header names each column once: a second column of a name would be ignored.
void checkDistinctNames(const std::string& path, int lineNumber, const std::vector<std::string>& names)
{
    std::map<std::string, std::size_t> first; // name -> its 0-based field
    for (std::size_t k = 0; k < names.size(); ++k)
    {
        const auto [it, added] = first.emplace(names[k], k);
        if (!added)
        {
            throw InputError(path, lineNumber, 1,
                             "column '" + names[k] + "' appears twice in the header (fields " +
                                 std::to_string(it->second + 1) + " and " + std::to_string(k + 1) +
                                 "); expected each column name once");
        }
    }
}

int indexOf(const std::vector<std::string>& names, const std::string& name)
{
    for (std::size_t k = 0; k < names.size(); ++k)
    {
        if (names[k] == name)
        {
            return static_cast<int>(k);
        }
    }
    return -1;
}
// The file's header and rows, one line at a time.
struct TargetReader
{
    const std::string& path;
    const std::string& column;
    std::vector<std::string> header{};
    int timeIndex = -1;
    int valueIndex = -1;
    int headerLine = 0;
    TargetColumn out{};

    void readHeader(int lineNumber, const std::vector<std::string>& row)
    {
        header = row;
        headerLine = lineNumber;
        checkDistinctNames(path, lineNumber, header);
        timeIndex = indexOf(header, "time");
        valueIndex = indexOf(header, column);
        if (timeIndex < 0)
        {
            throw InputError(path, lineNumber, 1,
                             "the header has no 'time' column (columns: " + joinNames(header) + ")");
        }
        if (valueIndex < 0)
        {
            throw InputError(path, lineNumber, 1,
                             "no column " + quotedName(column) + " in the header (columns: " +
                                 joinNames(header) + ")" + suggestionSuffix(column, header, false));
        }
    }

    void readRow(int lineNumber, const std::vector<std::string>& row)
    {
        if (row.size() != header.size())
        {
            throw InputError(path, lineNumber, 1,
                             "expected " + std::to_string(header.size()) +
                                 " comma-separated values (as the header on line " +
                                 std::to_string(headerLine) + "), got " + std::to_string(row.size()));
        }
        double numbers[2] = {0.0, 0.0};
        const int indices[2] = {timeIndex, valueIndex};
        for (int k = 0; k < 2; ++k)
        {
            const std::string& field = row[static_cast<std::size_t>(indices[k])];
            const std::optional<double> number = parseFiniteNumber(field);
            numbers[k] = number.value_or(0.0);
            if (!number)
            {
                throw InputError(path, lineNumber, 1,
                                 "expected a finite number in column '" +
                                     header[static_cast<std::size_t>(indices[k])] + "', got '" + field + "'");
            }
        }
        if (!out.times.empty() && !(numbers[0] > out.times.back()))
        {
            std::ostringstream message;
            message << "times must increase: time " << numbers[0] << " after " << out.times.back();
            throw InputError(path, lineNumber, 1, message.str());
        }
        out.times.push_back(numbers[0]);
        out.values.push_back(numbers[1]);
        out.lines.push_back(lineNumber);
    }
};
} // namespace

TargetColumn readTargetColumn(const std::string& path, const std::string& column)
{
    const std::string text = readTextFile(path, "target table file");
    std::stringstream in(text);
    std::string line;
    int lineNumber = 0;
    TargetReader reader{path, column};
    while (std::getline(in, line))
    {
        ++lineNumber;
        const std::string content = trimmed(line);
        if (content.empty() || content.front() == '#')
        {
            continue;
        }
        if (reader.header.empty())
        {
            reader.readHeader(lineNumber, fields(content));
        }
        else
        {
            reader.readRow(lineNumber, fields(content));
        }
    }
    if (reader.header.empty())
    {
        throw InputError(path, 0, 0, "no header line; expected column names, one of them 'time'");
    }
    if (reader.out.times.empty())
    {
        throw InputError(path, reader.headerLine, 1, "no rows of values after the header");
    }
    return std::move(reader.out);
}

} // namespace frontier::io::detail
