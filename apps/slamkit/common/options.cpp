#include "common/options.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "slamkit/runners/common/shard.hpp"

namespace slamkit::app {

namespace {

CLI::Validator NumberCheck(const std::string& description, bool (*ok)(double)) {
  return CLI::Validator(
      [description, ok](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value)) {
          return fmt::format("must be a number {}, got '{}'", description, text);
        }
        if (!std::isfinite(value) || !ok(value)) {
          return fmt::format("must be {}, got {}", description, text);
        }
        return {};
      },
      "NUMBER " + description);
}

}  // namespace

// "1-5", "1,3,7" or "2" as the list of seeds.
std::vector<std::uint64_t> ParseSeeds(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    const std::size_t dash = part.find('-');
    try {
      std::size_t used = 0;
      const std::uint64_t lo = std::stoull(part.substr(0, dash), &used);
      if (used != part.substr(0, dash).size() || part[0] == '-') throw std::invalid_argument("");
      std::uint64_t hi = lo;
      if (dash != std::string::npos) {
        const std::string rest = part.substr(dash + 1);
        hi = std::stoull(rest, &used);
        if (used != rest.size() || rest.empty() || rest[0] == '-') throw std::invalid_argument("");
      }
      if (hi < lo || hi - lo >= 1000) throw std::invalid_argument("");
      for (std::uint64_t s = lo; s <= hi; ++s) seeds.push_back(s);
    } catch (const std::exception&) {
      throw InputError(fmt::format("--seeds '{}': expected seeds such as 1-5 or 1,3,7 (a range "
                                   "of at most 1000)",
                                   text));
    }
    start = comma + 1;
  }
  return seeds;
}

const char* AssociationName(AssociationMethod m) {
  switch (m) {
    case AssociationMethod::kKnown: return "known";
    case AssociationMethod::kJointCompatibility: return "joint-compatibility";
    case AssociationMethod::kMaximumLikelihood: return "maximum-likelihood";
    case AssociationMethod::kGlobalNearestNeighbour: return "global-nearest-neighbour";
    case AssociationMethod::kNearestNeighbour: break;
  }
  return "nearest-neighbour";
}

CLI::Validator PositiveNumber() {
  return NumberCheck("> 0", [](double v) { return v > 0.0; });
}

CLI::Validator NonNegativeNumber() {
  return NumberCheck(">= 0", [](double v) { return v >= 0.0; });
}

CLI::Validator ShardText() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          ParseShard(text);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "K/N");
}

CLI::Validator SeedNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits || !CLI::detail::lexical_cast(text, value)) {
          return fmt::format("must be a whole number from 0 to 18446744073709551615, got '{}'",
                             text);
        }
        return {};
      },
      "SEED");
}

namespace {

std::string HelpOf(const config::Param& p) {
  return p.unit.empty() ? p.help : fmt::format("{} [{}]", p.help, p.unit);
}

template <typename Real>
CLI::Option* AddNumber(CLI::App* cmd, const config::Param& p, Real* v) {
  CLI::Option* o = cmd->add_option(p.flag, *v, HelpOf(p))->capture_default_str();
  if (p.bound == config::Bound::kFinite) {
    o->check(NumberCheck("finite", [](double) { return true; }));
  }
  if (p.bound == config::Bound::kPositive) o->check(PositiveNumber());
  if (p.bound == config::Bound::kNonNegative) o->check(NonNegativeNumber());
  if (std::isfinite(p.max)) o->check(CLI::Range(-std::numeric_limits<double>::max(), p.max));
  return o;
}

CLI::Option* AddChoice(CLI::App* cmd, const config::Param& p, const config::ChoiceRef& c) {
  return cmd
      ->add_option_function<std::string>(
          p.flag,
          [c](const std::string& name) {
            for (std::size_t i = 0; i < c.names.size(); ++i) {
              if (c.names[i] == name) c.set(static_cast<int>(i));
            }
          },
          HelpOf(p))
      ->transform(CLI::IsMember(c.names, CLI::ignore_case))
      ->default_str(c.names.at(c.get()));
}

CLI::Option* AddParamOption(CLI::App* cmd, const config::Param& p) {
  struct Visitor {
    CLI::App* cmd;
    const config::Param& p;
    CLI::Option* operator()(double* v) const {
      return p.degrees ? Unsupported() : AddNumber(cmd, p, v);
    }
    CLI::Option* operator()(float* v) const { return AddNumber(cmd, p, v); }
    CLI::Option* operator()(int* v) const {
      return cmd->add_option(p.flag, *v, HelpOf(p))
          ->capture_default_str()
          ->check(CLI::Range(p.min, p.max_int));
    }
    CLI::Option* operator()(long* v) const {
      return cmd->add_option(p.flag, *v, HelpOf(p))
          ->capture_default_str()
          ->check(CLI::Range(p.min, p.max_int));
    }
    CLI::Option* operator()(std::string* v) const {
      return cmd->add_option(p.flag, *v, HelpOf(p))->capture_default_str();
    }
    // Kinds no flag takes yet: a table giving them one is a mistake of the code.
    CLI::Option* operator()(Eigen::Vector2d*) const { return Unsupported(); }
    CLI::Option* operator()(std::optional<double>*) const { return Unsupported(); }
    CLI::Option* operator()(std::monostate) const { return Unsupported(); }
    CLI::Option* Unsupported() const {
      throw std::logic_error("AddParamOptions: no command-line kind for " + p.Path());
    }
    CLI::Option* operator()(std::uint64_t* v) const {
      return cmd->add_option(p.flag, *v, HelpOf(p))->check(SeedNumber())->capture_default_str();
    }
    CLI::Option* operator()(bool* v) const { return cmd->add_flag(p.flag, *v, HelpOf(p)); }
    CLI::Option* operator()(const config::ChoiceRef& c) const { return AddChoice(cmd, p, c); }
  };
  return std::visit(Visitor{cmd, p}, p.target);
}

}  // namespace

std::vector<CLI::Option*> AddParamOptions(CLI::App* cmd, const config::ParamTable& table) {
  std::vector<CLI::Option*> options;
  for (const config::Param& p : table) {
    if (!p.flag.empty()) options.push_back(AddParamOption(cmd, p));
  }
  return options;
}

void AddExamples(CLI::App* cmd, std::vector<std::string> examples) {
  cmd->footer([cmd, examples = std::move(examples)] {
    const CLI::App* root = cmd;
    while (root->get_parent() != nullptr) root = root->get_parent();
    const std::string program = root->get_name().empty() ? "slamkit" : root->get_name();
    std::string text = "Examples (from the repository root):";
    for (const std::string& example : examples) {
      text += "\n  " + program + " " + cmd->get_name() + " " + example;
    }
    return text;
  });
}

}  // namespace slamkit::app
