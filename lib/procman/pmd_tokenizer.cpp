#include "procman/pmd_tokenizer.h"

#include <cctype>

namespace slide::procman {

const char* describe(PmdToken::Type t) {
  switch (t) {
    case PmdToken::kIdent: return "identifier";
    case PmdToken::kString: return "string";
    case PmdToken::kInteger: return "integer";
    case PmdToken::kOpen: return "'{'";
    case PmdToken::kClose: return "'}'";
    case PmdToken::kAssign: return "'='";
    case PmdToken::kEnd: return "';'";
    case PmdToken::kEof: return "end of file";
  }
  return "?";
}

std::vector<PmdToken> tokenizePmd(const std::string& text, const std::string& file) {
  std::vector<PmdToken> out;
  int line = 1, col = 1;
  std::size_t i = 0;
  auto advance = [&]() {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
    ++i;
  };
  auto isIdentChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; };
  while (i < text.size()) {
    const char c = text[i];
    const SourcePos pos{line, col};
    if (std::isspace(static_cast<unsigned char>(c))) {
      advance();
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') advance();
    } else if (c == '{' || c == '}' || c == '=' || c == ';') {
      const PmdToken::Type t = c == '{' ? PmdToken::kOpen : c == '}' ? PmdToken::kClose
                               : c == '=' ? PmdToken::kAssign : PmdToken::kEnd;
      out.push_back({t, std::string(1, c), pos});
      advance();
    } else if (c == '"') {
      advance();
      std::string s;
      while (true) {
        if (i >= text.size() || text[i] == '\n') throw PmdError(file, pos, "unterminated string");
        if (text[i] == '"') break;
        if (text[i] == '\\' && i + 1 < text.size() && text[i + 1] != '\n') {
          advance();
          const char e = text[i];
          s += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
        } else {
          s += text[i];
        }
        advance();
      }
      advance();
      out.push_back({PmdToken::kString, s, pos});
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::string s;
      while (i < text.size() && isIdentChar(text[i])) {
        s += text[i];
        advance();
      }
      out.push_back({PmdToken::kIdent, s, pos});
    } else if (std::isdigit(static_cast<unsigned char>(c))) {
      std::string s;
      while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
        s += text[i];
        advance();
      }
      out.push_back({PmdToken::kInteger, s, pos});
    } else {
      throw PmdError(file, pos, std::string("invalid character '") + c + "'");
    }
  }
  out.push_back({PmdToken::kEof, "", {line, col}});
  return out;
}

}  // namespace slide::procman
