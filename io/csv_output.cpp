// io/csv_output.cpp: comment line, numbers, names and atomic writing of the run's CSV files.
#include "io/csv_output.h"

#include "io/atomic_file.h"

#include <charconv>

namespace frontier::io
{

namespace
{
int hexDigit(char c)
{
    if (c >= '0' && c <= '9')
    {
        return c - '0';
    }
    if (c >= 'A' && c <= 'F')
    {
        return c - 'A' + 10;
    }
    if (c >= 'a' && c <= 'f')
    {
        return c - 'a' + 10;
    }
    return -1;
}
} // namespace

std::string metadataPrefix(const std::string& kind)
{
    return "# frontier " + kind + ":";
}

std::string encodeMetadataField(const std::string& text)
{
    static constexpr char hex[] = "0123456789ABCDEF";
    std::string out;
    for (const char c : text)
    {
        const auto u = static_cast<unsigned char>(c);
        if (c == '%' || c == ' ' || c == '=' || c == ',' || u < 0x20 || u == 0x7f)
        {
            out += '%';
            out += hex[u >> 4];
            out += hex[u & 15];
        }
        else
        {
            out += c;
        }
    }
    return out;
}

std::string decodeMetadataField(std::string_view text)
{
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i)
    {
        if (text[i] == '%' && i + 2 < text.size() && hexDigit(text[i + 1]) >= 0 && hexDigit(text[i + 2]) >= 0)
        {
            out += static_cast<char>(hexDigit(text[i + 1]) * 16 + hexDigit(text[i + 2]));
            i += 2;
        }
        else
        {
            out += text[i];
        }
    }
    return out;
}

void appendNumber(std::string& out, double value)
{
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 17);
    out.append(buffer, result.ptr);
}

void appendName(std::string& out, const std::string& name)
{
    if (name.find_first_of(",\"\r\n#") == std::string::npos)
    {
        out += name;
        return;
    }
    out += '"';
    for (const char c : name)
    {
        out += c;
        if (c == '"')
        {
            out += '"';
        }
    }
    out += '"';
}

CsvFile::CsvFile(const std::string& path, const std::string& kind, const FileMetadata& metadata,
                 const char* header)
    : mFile(std::make_unique<AtomicFile>(path))
{
    std::string head = metadataPrefix(kind);
    for (const auto& [key, value] : metadata)
    {
        head += ' ' + encodeMetadataField(key) + '=' + encodeMetadataField(value);
    }
    head += '\n';
    head += header;
    head += '\n';
    mFile->write(head);
}

CsvFile::~CsvFile() = default;

void CsvFile::writeRow(const std::string& line)
{
    mFile->write(line);
    mFile->write("\n", 1);
    ++mRows;
}

void CsvFile::commit()
{
    mFile->commit();
}

void CsvFile::commitAs(const std::string& path)
{
    mFile->commitAs(path);
}

} // namespace frontier::io
