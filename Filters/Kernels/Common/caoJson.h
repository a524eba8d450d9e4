#ifndef caoJson_h
#define caoJson_h

/**
 * @file caoJson.h
 * @brief Text as the inside of a JSON string: the one escaping of the
 * project's JSON reports (the mapper's and the pass's frame reports, `cao
 * --json`).
 *
 * A quote and a backslash get a backslash; a control character (below
 * 0x20) its short escape (\n, \t, \r, \b, \f) or \u00XX. Other bytes pass as
 * they are (UTF-8 text stays UTF-8).
 */

#include <string>

namespace cao
{
inline std::string JsonEscape(const std::string& text)
{
  static const char* const hex = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char c : text)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    switch (c)
    {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (u < 0x20)
        {
          out += "\\u00";
          out += hex[u >> 4];
          out += hex[u & 15];
        }
        else
          out += c;
    }
  }
  return out;
}
}

#endif
