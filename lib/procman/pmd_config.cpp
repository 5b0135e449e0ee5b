#include "procman/pmd_config.h"

#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "procman/pmd_tokenizer.h"

namespace slide::procman {

PmdError::PmdError(const std::string& file, SourcePos p, const std::string& what)
    : std::runtime_error(p.line > 0 ? file + ":" + std::to_string(p.line) + ":" + std::to_string(p.column) + ": " + what
                                     : file + ": " + what),
      pos(p) {}

const PmdScript* PmdConfig::findScript(const std::string& name) const {
  for (const PmdScript& s : scripts)
    if (s.name == name) return &s;
  return nullptr;
}

const char* toString(WaitStatus s) {
  return s == WaitStatus::kRunning ? "running" : s == WaitStatus::kStopped ? "stopped" : "none";
}

namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& file) : file_(file), toks_(tokenizePmd(text, file)) {}

  PmdConfig parse() {
    PmdConfig cfg;
    cfg.file = file_;
    while (peek().type != PmdToken::kEof) {
      const PmdToken& t = expect(PmdToken::kIdent, "'cmd', 'group' or 'script'");
      if (t.text == "cmd") parseCommand("", cfg);
      else if (t.text == "group") parseGroup("", cfg);
      else if (t.text == "script") parseScript(cfg);
      else fail(t, "expected 'cmd', 'group' or 'script', found '" + t.text + "'");
    }
    checkUnique(cfg);
    return cfg;
  }

 private:
  const PmdToken& peek() const { return toks_[i_]; }
  const PmdToken& next() { return toks_[i_ < toks_.size() - 1 ? i_++ : i_]; }
  [[noreturn]] void fail(const PmdToken& t, const std::string& what) const { throw PmdError(file_, t.pos, what); }

  const PmdToken& expect(PmdToken::Type type, const std::string& what) {
    const PmdToken& t = next();
    if (t.type != type) {
      const bool named = t.type == PmdToken::kIdent || t.type == PmdToken::kInteger;
      const std::string found = t.type == PmdToken::kString ? "string \"" + t.text + "\""
                                : named ? std::string(describe(t.type)) + " '" + t.text + "'" : describe(t.type);
      fail(t, "expected " + what + ", found " + found);
    }
    return t;
  }

  const PmdToken& expectWord(const std::string& word) {
    const PmdToken& t = expect(PmdToken::kIdent, "'" + word + "'");
    if (t.text != word) fail(t, "expected '" + word + "', found '" + t.text + "'");
    return t;
  }

  int64_t integer(const PmdToken& t) const {
    try {
      return std::stoll(t.text);
    } catch (const std::exception&) {
      fail(t, "integer out of range: " + t.text);
    }
  }

  void parseGroup(const std::string& parent, PmdConfig& cfg) {
    const PmdToken& name = expect(PmdToken::kString, "group name string");
    if (name.text.find('/') != std::string::npos) fail(name, "'/' is not allowed in a group name");
    if (name.text.find_first_not_of(" \t") == std::string::npos) fail(name, "empty group name");
    const std::string path = parent.empty() ? name.text : parent + "/" + name.text;
    expect(PmdToken::kOpen, "'{'");
    while (peek().type == PmdToken::kIdent) {
      const PmdToken& t = next();
      if (t.text == "cmd") parseCommand(path, cfg);
      else if (t.text == "group") parseGroup(path, cfg);
      else fail(t, "expected 'cmd' or 'group', found '" + t.text + "'");
    }
    expect(PmdToken::kClose, "'}', 'cmd' or 'group'");
  }

  void parseCommand(const std::string& group, PmdConfig& cfg) {
    PmdCommand cmd;
    cmd.pos = toks_[i_ - 1].pos;
    cmd.spec.group = group;
    cmd.spec.stop_signal = SIGINT;
    cmd.spec.stop_time_allowed = 7;
    const PmdToken& id = expect(PmdToken::kString, "command id string");
    if (id.text.empty()) fail(id, "empty command id");
    if (id.text.find('/') != std::string::npos) fail(id, "'/' is not allowed in a command id");
    cmd.spec.id = id.text;
    expect(PmdToken::kOpen, "'{'");
    std::set<std::string> seen;
    while (peek().type == PmdToken::kIdent) {
      const PmdToken& key = next();
      if (!seen.insert(key.text == "host" ? "deputy" : key.text).second) fail(key, "attribute '" + key.text + "' given twice");
      expect(PmdToken::kAssign, "'='");
      if (key.text == "exec" || key.text == "deputy" || key.text == "host" || key.text == "group") {
        const PmdToken& v = expect(PmdToken::kString, "string value for '" + key.text + "'");
        if (key.text == "exec") cmd.spec.exec = v.text;
        else if (key.text == "group") cmd.spec.group = group.empty() ? v.text : group + "/" + v.text;
        else cmd.deputy = v.text;
      } else if (key.text == "auto_respawn") {
        const PmdToken& v = next();
        if ((v.type != PmdToken::kString && v.type != PmdToken::kIdent) || (v.text != "true" && v.text != "false"))
          fail(v, "auto_respawn must be \"true\" or \"false\"");
        cmd.spec.auto_respawn = v.text == "true";
      } else if (key.text == "stop_signal" || key.text == "stop_time_allowed") {
        const PmdToken& v = expect(PmdToken::kInteger, "integer value for '" + key.text + "'");
        const int64_t n = integer(v);
        if (key.text == "stop_signal" && (n < 1 || n > 64)) fail(v, "stop_signal must be a signal number 1..64");
        if (key.text == "stop_time_allowed" && n < 1) fail(v, "stop_time_allowed must be at least 1 (seconds)");
        if (key.text == "stop_signal") cmd.spec.stop_signal = static_cast<int>(n);
        else cmd.spec.stop_time_allowed = static_cast<double>(n);
      } else {
        fail(key, "unknown command attribute '" + key.text +
                      "' (expected exec, deputy, host, group, auto_respawn, stop_signal, stop_time_allowed)");
      }
      expect(PmdToken::kEnd, "';'");
    }
    const PmdToken& close = expect(PmdToken::kClose, "'}' or an attribute name");
    if (cmd.spec.exec.empty()) fail(close, "command '" + cmd.spec.id + "' has no exec");
    if (cmd.deputy.empty()) fail(close, "command '" + cmd.spec.id + "' has no deputy");
    cfg.commands.push_back(cmd);
  }

  TargetKind target(ScriptAction& a) {
    const PmdToken& t = expect(PmdToken::kIdent, "'everything', 'cmd' or 'group'");
    if (t.text == "everything") return TargetKind::kEverything;
    if (t.text != "cmd" && t.text != "group") fail(t, "expected 'everything', 'cmd' or 'group', found '" + t.text + "'");
    a.name = expect(PmdToken::kString, t.text + " name string").text;
    return t.text == "cmd" ? TargetKind::kCommand : TargetKind::kGroup;
  }

  WaitStatus status() {
    const PmdToken& s = expect(PmdToken::kString, "\"running\" or \"stopped\"");
    if (s.text == "running") return WaitStatus::kRunning;
    if (s.text == "stopped") return WaitStatus::kStopped;
    fail(s, "expected \"running\" or \"stopped\", found \"" + s.text + "\"");
  }

  void parseScript(PmdConfig& cfg) {
    PmdScript script;
    script.pos = toks_[i_ - 1].pos;
    const PmdToken& name = expect(PmdToken::kString, "script name string");
    if (cfg.findScript(name.text)) fail(name, "script '" + name.text + "' defined twice");
    script.name = name.text;
    expect(PmdToken::kOpen, "'{'");
    while (peek().type == PmdToken::kIdent) {
      const PmdToken& verb = next();
      ScriptAction a;
      a.pos = verb.pos;
      if (verb.text == "start" || verb.text == "stop" || verb.text == "restart") {
        a.kind = verb.text == "start" ? ScriptAction::kStart : verb.text == "stop" ? ScriptAction::kStop : ScriptAction::kRestart;
        a.target = target(a);
        if (peek().type == PmdToken::kIdent) {
          expectWord("wait");
          a.wait = status();
        }
      } else if (verb.text == "wait") {
        const PmdToken& what = expect(PmdToken::kIdent, "'ms', 'cmd' or 'group'");
        if (what.text == "ms") {
          a.kind = ScriptAction::kWaitMs;
          a.ms = integer(expect(PmdToken::kInteger, "a number of milliseconds"));
        } else if (what.text == "cmd" || what.text == "group") {
          a.kind = ScriptAction::kWaitStatus;
          a.target = what.text == "cmd" ? TargetKind::kCommand : TargetKind::kGroup;
          a.name = expect(PmdToken::kString, what.text + " name string").text;
          expectWord("status");
          a.wait = status();
        } else {
          fail(what, "expected 'ms', 'cmd' or 'group', found '" + what.text + "'");
        }
      } else if (verb.text == "run_script") {
        a.kind = ScriptAction::kRunScript;
        a.name = expect(PmdToken::kString, "script name string").text;
      } else {
        fail(verb, "expected start, stop, restart, wait or run_script, found '" + verb.text + "'");
      }
      expect(PmdToken::kEnd, "';'");
      script.actions.push_back(a);
    }
    expect(PmdToken::kClose, "'}' or a script action");
    cfg.scripts.push_back(script);
  }

  void checkUnique(const PmdConfig& cfg) const {
    std::set<std::pair<std::string, std::string>> seen;
    for (const PmdCommand& c : cfg.commands)
      if (!seen.insert({c.deputy, c.spec.id}).second)
        throw PmdError(file_, c.pos, "command '" + c.spec.id + "' defined twice for deputy '" + c.deputy + "'");
  }

  std::string file_;
  std::vector<PmdToken> toks_;
  std::size_t i_ = 0;
};

}  // namespace

PmdConfig parsePmd(const std::string& text, const std::string& file) { return Parser(text, file).parse(); }

PmdConfig loadPmd(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw PmdError(path, {0, 0}, "cannot read the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parsePmd(ss.str(), path);
}

}  // namespace slide::procman
