#include "lab/text_checks.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "lab/values.h"
#include "output/csv_writer.h"
#include "particles/integrator.h"

namespace lab {

namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += (text.empty() ? "" : "\n") + line;
  return text;
}

// A data file: its header and rows.
struct Table {
  std::string name;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  std::size_t column(const std::string& col) const {
    const auto found = std::find(header.begin(), header.end(), col);
    if (found == header.end()) throw std::runtime_error("check: " + name + " has no column '" + col + "'");
    return static_cast<std::size_t>(found - header.begin());
  }
  bool has(const std::string& col) const { return std::count(header.begin(), header.end(), col) > 0; }
  std::string rowText(std::size_t r) const {
    std::string text;
    for (const auto& cell : rows[r]) text += (text.empty() ? "" : ",") + cell;
    return "row " + std::to_string(r + 1) + " (" + text + ")";
  }
};

Table readTable(const std::string& dataDir, const std::string& name) {
  if (name.find('/') != std::string::npos || name.find("..") != std::string::npos)
    throw std::runtime_error("check: '" + name + "' is not a file of the data directory");
  std::ifstream in(dataDir + "/" + name);
  if (!in) throw std::runtime_error("check: cannot read " + dataDir + "/" + name);
  Table table;
  table.name = name;
  std::string line;
  if (std::getline(in, line)) table.header = output::csvSplit(line);
  while (std::getline(in, line))
    if (!line.empty()) table.rows.push_back(output::csvSplit(line));
  return table;
}

// A number as the data writes it ("0.07", "1e-3"); nullopt-like NaN for text.
double numberOf(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  return end != begin && *end == '\0' ? value : std::nan("");
}

// A value of values.csv compared as the number it starts with after any sign of
// inequality ("≥ 0.4974" reads 0.4974, "p ≤ 0.0013" reads 0.0013).
double leadingNumber(const std::string& text) {
  const std::size_t at = text.find_first_of("0123456789.-");
  if (at == std::string::npos) return std::nan("");
  for (std::size_t k = 0; k < at; ++k) {  // only signs of inequality (≤, ≥: bytes above 0x7f) and "p" before it
    const unsigned char c = static_cast<unsigned char>(text[k]);
    if (!(c >= 0x80 || c == ' ' || c == 'p' || c == '<' || c == '>' || c == '=' || c == '~')) return std::nan("");
  }
  return std::strtod(text.c_str() + at, nullptr);
}

const std::vector<std::string> kOperators = {"<=", ">=", "!=", "<", ">", "="};

bool holds(int order, const std::string& op) {
  if (op == "<") return order < 0;
  if (op == "<=") return order <= 0;
  if (op == ">") return order > 0;
  if (op == ">=") return order >= 0;
  if (op == "=") return order == 0;
  if (op == "!=") return order != 0;
  throw std::runtime_error("check: unknown comparison '" + op + "'");
}

int orderOf(double x, double y) { return x < y ? -1 : x > y ? 1 : 0; }

bool compare(const std::string& a, const std::string& op, const std::string& b) {
  const double x = numberOf(a), y = numberOf(b);
  if (!std::isnan(x) && !std::isnan(y)) return holds(orderOf(x, y), op);
  return holds(a.compare(b) < 0 ? -1 : a.compare(b) > 0 ? 1 : 0, op);
}

// COLUMN OP VALUE in one word.
struct Condition {
  std::string column, op, value;
};

Condition parseCondition(const std::string& word) {
  for (const std::string& op : kOperators) {
    const std::size_t at = word.find(op);
    if (at != std::string::npos && at > 0) return {word.substr(0, at), op, word.substr(at + op.size())};
  }
  throw std::runtime_error("check: '" + word + "' is not a condition COLUMN OP VALUE");
}

std::vector<Condition> conditions(const std::vector<std::string>& words, std::size_t from) {
  std::vector<Condition> out;
  for (std::size_t k = from; k < words.size(); ++k) out.push_back(parseCondition(words[k]));
  return out;
}

// A column's cell, or the number given in its place.
std::string operand(const Table& table, std::size_t row, const std::string& word) {
  return table.has(word) ? table.rows[row][table.column(word)] : word;
}

// The rows meeting every condition, in file order.
std::vector<std::size_t> matching(const Table& table, const std::vector<Condition>& conds) {
  std::vector<std::size_t> rows;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    bool meets = true;
    for (const Condition& c : conds)
      meets = meets && compare(table.rows[r].at(table.column(c.column)), c.op, operand(table, r, c.value));
    if (meets) rows.push_back(r);
  }
  return rows;
}

std::string conditionsText(const std::vector<Condition>& conds) {
  std::string text;
  for (const auto& c : conds) text += (text.empty() ? "" : " and ") + c.column + c.op + c.value;
  return text.empty() ? "every row" : text;
}

void requireWords(const std::vector<std::string>& words, std::size_t count, const std::string& form) {
  if (words.size() < count) throw std::runtime_error("check: '" + joined(words) + "' is not of the form " + form);
}

std::string checkRows(const std::vector<std::string>& w, const std::string& dataDir) {
  const std::string& kind = w[0];
  requireWords(w, 2, kind + " FILE ...");
  const Table table = readTable(dataDir, w[1]);
  if (kind == "never" || kind == "some") {
    const std::vector<Condition> conds = conditions(w, 2);
    const std::vector<std::size_t> rows = matching(table, conds);
    if (kind == "never" && !rows.empty()) return table.name + " " + table.rowText(rows[0]) + " has " + conditionsText(conds);
    if (kind == "some" && rows.empty()) return "no row of " + table.name + " has " + conditionsText(conds);
    return "";
  }
  if (kind == "every") {
    requireWords(w, 5, "every FILE A OP B [COND...]");
    const std::vector<Condition> conds = conditions(w, 5);
    const std::size_t a = table.column(w[2]);
    for (std::size_t r : matching(table, conds))
      if (!compare(table.rows[r][a], w[3], operand(table, r, w[4])))
        return table.name + " " + table.rowText(r) + " has " + w[2] + " = " + table.rows[r][a] + ", not " + w[3] +
               " " + operand(table, r, w[4]);
    return "";
  }
  // increasing / decreasing
  requireWords(w, 4, kind + " FILE X Y [COND...]");
  const std::size_t x = table.column(w[2]), y = table.column(w[3]);
  std::vector<std::size_t> rows = matching(table, conditions(w, 4));
  std::stable_sort(rows.begin(), rows.end(), [&](std::size_t p, std::size_t q) {
    return numberOf(table.rows[p][x]) < numberOf(table.rows[q][x]);
  });
  const std::string op = kind == "increasing" ? ">" : "<";
  for (std::size_t k = 1; k < rows.size(); ++k)
    if (!compare(table.rows[rows[k]][y], op, table.rows[rows[k - 1]][y]))
      return table.name + ": " + w[3] + " is not " + kind + " in " + w[2] + ": " + table.rows[rows[k - 1]][y] +
             " at " + w[2] + " = " + table.rows[rows[k - 1]][x] + ", then " + table.rows[rows[k]][y] + " at " +
             table.rows[rows[k]][x];
  return "";
}

std::string checkValue(const std::vector<std::string>& w, const std::string& dataDir) {
  requireWords(w, 4, "value KEY OP KEY|NUMBER");
  const auto values = readValues(dataDir);
  const auto read = [&](const std::string& key) -> std::string {
    const auto found = values.find(key);
    if (found == values.end()) throw std::runtime_error("check: no value '" + key + "' in values.csv");
    return found->second;
  };
  const std::string a = read(w[1]);
  // B: a number, a key, or FACTOR*KEY.
  double factor = 1.0;
  std::string key = w[3];
  if (const std::size_t star = key.find('*'); star != std::string::npos && !std::isnan(numberOf(key.substr(0, star))))
    factor = numberOf(key.substr(0, star)), key = key.substr(star + 1);
  const bool numberGiven = !std::isnan(numberOf(key));
  const std::string b = numberGiven ? key : read(key);
  const double x = leadingNumber(a), y = factor * leadingNumber(b);
  if (std::isnan(x) || std::isnan(y))
    throw std::runtime_error("check: '" + a + "' or '" + b + "' is not a number (" + joined(w) + ")");
  if (holds(orderOf(x, y), w[2])) return "";
  return w[1] + " = " + a + " is not " + w[2] + " " + (numberGiven ? b : w[3] + " (" + key + " = " + b + ")");
}

// The report's ways of naming an integrator, longest first, and the command-line name each means.
std::vector<std::pair<std::string, std::string>> integratorNames() {
  std::vector<std::pair<std::string, std::string>> names = {{"explicit euler", "euler"}};
  for (const auto& info : particles::integratorTable()) {
    std::string prose = info.name;
    std::replace(prose.begin(), prose.end(), '-', ' ');
    names.push_back({info.name, info.name});
    if (prose != info.name) names.push_back({prose, info.name});
  }
  std::stable_sort(names.begin(), names.end(),
                   [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
  return names;
}

// Where the cost experiment names `integrator` the cheapest pick, or "".
std::string cheapestPick(const std::string& integrator, const std::string& dataDir) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> sources = {
      {"cost_of_accuracy.csv", {"integrator=" + integrator, "cheapest=1"}},
      {"cost_vs_size.csv", {"integrator=" + integrator}}};
  for (const auto& [file, conds] : sources) {
    std::ifstream probe(dataDir + "/" + file);
    if (!probe) continue;
    const Table table = readTable(dataDir, file);
    if (!table.has("integrator") || (file == "cost_of_accuracy.csv" && !table.has("cheapest"))) continue;
    std::vector<Condition> parsed;
    for (const auto& c : conds) parsed.push_back(parseCondition(c));
    const std::vector<std::size_t> rows = matching(table, parsed);
    if (!rows.empty()) return file + " " + table.rowText(rows[0]);
  }
  return "";
}

// The text in lower case with Markdown emphasis and code marks dropped (line breaks kept).
std::string unmarked(const std::string& text) {
  std::string out;
  for (char c : text)
    if (c != '*' && c != '_' && c != '`') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// unmarked, with every run of blanks (line breaks too) as one space.
std::string plainWords(const std::string& text) {
  std::string out;
  for (char c : unmarked(text)) {
    const bool blank = std::isspace(static_cast<unsigned char>(c));
    if (blank && (out.empty() || out.back() == ' ')) continue;
    out += blank ? ' ' : c;
  }
  return out;
}

// The sentences of plain text: split at a full stop followed by a blank, at a blank line and
// at a table row (a line starting with '|').
std::vector<std::string> sentencesOf(const std::string& text) {
  std::vector<std::string> sentences;
  std::string current;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    const bool row = c == '\n' && k + 1 < text.size() && text[k + 1] == '|';
    const bool paragraph = c == '\n' && k + 1 < text.size() && text[k + 1] == '\n';
    const bool stop = c == '.' && (k + 1 == text.size() || std::isspace(static_cast<unsigned char>(text[k + 1])));
    if (!(row || paragraph)) current += c;
    if (row || paragraph || stop) {
      if (!current.empty()) sentences.push_back(current);
      current.clear();
    }
  }
  if (!current.empty()) sentences.push_back(current);
  return sentences;
}

// Steps called safe without the bound their runs support.
std::vector<std::string> unboundedSafeSteps(const std::string& text) {
  static const std::vector<std::string> kSafe = {"safe dt", "safe step", "safe time step", "certified dt",
                                                 "certified safe"};
  std::vector<std::string> found;
  for (const std::string& raw : sentencesOf(unmarked(text))) {
    const std::string sentence = plainWords(raw);
    if (sentence.find("p ≤") != std::string::npos || sentence.find("p <=") != std::string::npos) continue;
    for (const std::string& phrase : kSafe)
      if (sentence.find(phrase) != std::string::npos) {
        std::string shown = sentence.substr(0, 160);
        while (!shown.empty() && std::isspace(static_cast<unsigned char>(shown.front()))) shown.erase(0, 1);
        found.push_back("the text calls a step \"" + phrase +
                        "\" without the failure bound its runs support (no \"p ≤\" in: \"" + shown + "\")");
        break;
      }
  }
  return found;
}

}  // namespace

ReportContradiction::ReportContradiction(const std::vector<std::string>& lines)
    : std::runtime_error(joined(lines)), found(lines) {}

std::string evaluateCheck(const std::string& check, const std::string& dataDir) {
  std::istringstream in(check);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  if (words.empty()) throw std::runtime_error("check: empty check");
  const std::string& kind = words[0];
  if (kind == "value") return checkValue(words, dataDir);
  if (kind == "never" || kind == "some" || kind == "every" || kind == "increasing" || kind == "decreasing")
    return checkRows(words, dataDir);
  throw std::runtime_error("check: unknown kind '" + kind +
                           "' (never, some, every, increasing, decreasing or value)");
}

std::vector<std::string> proseContradictions(const std::string& text, const std::string& dataDir) {
  std::vector<std::string> found;
  const std::string plain = plainWords(text);
  const auto names = integratorNames();
  for (std::size_t at = plain.find("never "); at != std::string::npos; at = plain.find("never ", at + 1)) {
    if (at > 0 && std::isalpha(static_cast<unsigned char>(plain[at - 1]))) continue;
    const std::size_t word = at + 6;
    for (const auto& [prose, integrator] : names) {
      if (plain.compare(word, prose.size(), prose) != 0) continue;
      const std::size_t end = word + prose.size();
      if (end < plain.size() && (std::isalnum(static_cast<unsigned char>(plain[end])) || plain[end] == '-')) continue;
      const std::string where = cheapestPick(integrator, dataDir);
      if (!where.empty())
        found.push_back("the text says \"never " + prose + "\", but the cost experiment picks " + integrator +
                        " as the cheapest: " + where);
      break;
    }
  }
  for (std::string& safe : unboundedSafeSteps(text)) found.push_back(std::move(safe));
  return found;
}

}  // namespace lab
