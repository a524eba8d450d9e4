// The one JSON escaping of the project's reports (caoJson.h): a quote, a
// backslash and every control character come out escaped, so that a frame
// report whose error quotes a file name or holds a line break still parses;
// other bytes, UTF-8 included, pass unchanged. Negative control: the
// escaping the mapper and `cao` used before (a line break made a space, a
// control character left raw) fails the control-character checks.
#include "caoJson.h"
#include "caoTestUtilities.h"

#include <string>

namespace
{
/// The former mapper's escaping: quotes and backslashes only, a newline to a space.
std::string Former(const std::string& text)
{
  std::string out;
  for (char c : text)
    out += (c == '"' || c == '\\' ? std::string("\\") + c : c == '\n' ? std::string(" ") : std::string(1, c));
  return out;
}

/// Whether `escaped` holds no raw control character and no unescaped quote.
bool JsonSafe(const std::string& escaped)
{
  for (std::size_t i = 0; i < escaped.size(); ++i)
  {
    const unsigned char c = static_cast<unsigned char>(escaped[i]);
    if (c < 0x20)
      return false;
    if (c == '\\')
    {
      ++i; // the escaped character
      continue;
    }
    if (c == '"')
      return false;
  }
  return true;
}
}

int TestJsonEscape(int, char*[])
{
  CAO_CHECK(cao::JsonEscape("plain text, 3.5 ms") == "plain text, 3.5 ms", "plain text changed");
  CAO_CHECK(cao::JsonEscape("the \"mesh\" C:\\x") == "the \\\"mesh\\\" C:\\\\x", "quote or backslash: %s",
    cao::JsonEscape("the \"mesh\" C:\\x").c_str());
  CAO_CHECK(cao::JsonEscape("a\nb\tc\rd") == "a\\nb\\tc\\rd", "line break or tab: %s",
    cao::JsonEscape("a\nb\tc\rd").c_str());
  const std::string control("x\x01y\x1f", 4);
  CAO_CHECK(cao::JsonEscape(control) == "x\\u0001y\\u001f", "control characters: %s",
    cao::JsonEscape(control).c_str());
  CAO_CHECK(cao::JsonEscape("\xc3\xa9t\xc3\xa9") == "\xc3\xa9t\xc3\xa9", "UTF-8 changed");
  CAO_CHECK(cao::JsonEscape("") .empty(), "empty text");
  // Every byte below 0x20, a quote and a backslash, in one text.
  std::string all;
  for (int c = 1; c < 0x20; ++c)
    all += static_cast<char>(c);
  all += "\"\\";
  CAO_CHECK(JsonSafe(cao::JsonEscape(all)), "an unescaped character remains: %s", cao::JsonEscape(all).c_str());
  // The control: the former escaping leaves control characters raw.
  CAO_CHECK(!JsonSafe(Former(all)), "the negative control passed: the check cannot fail");
  return 0;
}
