// Scheduling and register allocation of a FormulaTape (formula_tape.hpp):
// from the SSA instructions that the lowering in formula.cpp records to the
// straight-line TapeProgram that eval and slopes run.
#include "problems/formula_tape.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace rb {
namespace {

// -- from nodes to the tape ------------------------------------------------------

// Rough latencies in cycles, to tell which operand of an op is ready last.
int latency(TapeCode code) {
  switch (code) {
    case TapeCode::add:
    case TapeCode::sub:
    case TapeCode::mul:
    case TapeCode::add_c:
    case TapeCode::mul_c:
    case TapeCode::rsub_c:
    case TapeCode::neg: return 3;
    case TapeCode::div:
    case TapeCode::div_c:
    case TapeCode::rdiv_c: return 13;
    case TapeCode::sqrt: return 20;
    default: return 60;  // a libm call
  }
}

// The live instructions in the order the tape runs them, found by a
// depth-first walk from the outputs, the most urgent first: the gradient
// (N and its square root wait for it), then the Hessian, then f (which the
// right-hand side does not use). Of an op's operands, the one ready last is
// computed right before the op. So the longest chains pass their values on
// in a machine register (TapeOp::chained), and the first op reads its input
// from one. sin and cos of one argument become one op (partner), emitted
// when the first of the two is needed; wanted[i] is the value its consumer
// reads, which the op leaves in `last`.
struct Schedule {
  std::vector<int> order;    // node indices
  std::vector<int> partner;  // node merged with node i, or -1
  std::vector<int> wanted;   // for a merged node: the value to leave in `last`
};

Schedule schedule(const std::vector<TapeNode>& nodes, const std::array<int, 6>& outputs) {
  const std::size_t n = nodes.size();
  const auto node_of = [](int value) { return static_cast<std::size_t>(value - 2); };
  Schedule s;
  s.partner.assign(n, -1);
  s.wanted.assign(n, -1);
  std::map<std::pair<TapeCode, int>, int> trig;  // (sin or cos, argument) -> node
  std::vector<int> depth(n + 2, 0);              // of each value, in cycles
  for (std::size_t i = 0; i < n; ++i) {
    const TapeNode& node = nodes[i];
    depth[i + 2] =
        std::max(depth[static_cast<std::size_t>(node.a)], node.b >= 0 ? depth[static_cast<std::size_t>(node.b)] : 0) +
        latency(node.code);
    if (node.code != TapeCode::sin && node.code != TapeCode::cos) continue;
    const TapeCode other = node.code == TapeCode::sin ? TapeCode::cos : TapeCode::sin;
    const auto found = trig.find({other, node.a});
    if (found != trig.end()) {
      s.partner[i] = found->second;
      s.partner[static_cast<std::size_t>(found->second)] = static_cast<int>(i);
      trig.erase(found);
    } else {
      trig[{node.code, node.a}] = static_cast<int>(i);
    }
  }
  // outputs by urgency: the gradient, the Hessian, then f; deeper first
  const std::array<int, 6> urgency = {0, 2, 2, 1, 1, 1};
  std::array<std::size_t, 6> parts = {0, 1, 2, 3, 4, 5};
  const auto value_depth = [&](std::size_t part) {
    return outputs[part] >= 0 ? depth[static_cast<std::size_t>(outputs[part])] : 0;
  };
  std::stable_sort(parts.begin(), parts.end(), [&](std::size_t a, std::size_t b) {
    return std::make_pair(urgency[a], value_depth(a)) > std::make_pair(urgency[b], value_depth(b));
  });
  std::vector<bool> emitted(n, false);
  std::vector<std::pair<int, bool>> stack;  // (value, operands done)
  for (const std::size_t part : parts) {
    stack.push_back({outputs[part], false});
    while (!stack.empty()) {
      const auto [v, expanded] = stack.back();
      stack.pop_back();
      if (v < 2 || emitted[node_of(v)]) continue;
      const std::size_t i = node_of(v);
      if (expanded) {
        emitted[i] = true;
        if (s.partner[i] >= 0) {
          emitted[static_cast<std::size_t>(s.partner[i])] = true;
          s.wanted[i] = v;
        }
        s.order.push_back(static_cast<int>(i));
        continue;
      }
      stack.push_back({v, true});
      // visited in reverse order of pushing: the operand ready last goes last
      int a = nodes[i].a, b = nodes[i].b;
      if (b >= 0 && depth[static_cast<std::size_t>(b)] > depth[static_cast<std::size_t>(a)]) std::swap(a, b);
      stack.push_back({a, false});
      if (b >= 0) stack.push_back({b, false});
    }
  }
  return s;
}

}  // namespace

std::optional<TapeProgram> build_tape(const std::vector<TapeNode>& nodes, const std::array<int, 6>& outputs,
                                      const Jet2<double>& constants) {
  const Schedule sched = schedule(nodes, outputs);
  const std::vector<int>& order = sched.order;
  // last use of every value, in positions of `order`; outputs live to the end
  const int n_values = static_cast<int>(nodes.size()) + 2;
  std::vector<int> last_use(static_cast<std::size_t>(n_values), -1);
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    const TapeNode& node = nodes[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    for (const int v : {node.a, node.b})
      if (v >= 0) last_use[static_cast<std::size_t>(v)] = k;
  }
  for (const int v : outputs)
    if (v >= 0) last_use[static_cast<std::size_t>(v)] = static_cast<int>(order.size());

  // registers: x and y stay in 0 and 1; a value's register is free again
  // after its last use, and an instruction may write over its operands
  std::vector<int> reg(static_cast<std::size_t>(n_values), -1);
  reg[0] = 0;
  reg[1] = 1;
  std::vector<int> free_regs;
  int n_regs = 2;
  const auto allocate = [&](int value) {
    int r;
    if (free_regs.empty()) {
      r = n_regs++;
    } else {
      const auto lowest = std::min_element(free_regs.begin(), free_regs.end());
      r = *lowest;
      free_regs.erase(lowest);
    }
    reg[static_cast<std::size_t>(value)] = r;
    return static_cast<std::uint8_t>(r);
  };
  std::vector<TapeOp> ops;
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    const int i = order[static_cast<std::size_t>(k)];
    const TapeNode& node = nodes[static_cast<std::size_t>(i)];
    TapeOp op{node.code};
    op.c = node.c;
    op.a = static_cast<std::uint8_t>(reg[static_cast<std::size_t>(node.a)]);
    if (node.b >= 0) op.b = static_cast<std::uint8_t>(reg[static_cast<std::size_t>(node.b)]);
    for (const int v : {node.a, node.b == node.a ? -1 : node.b})
      if (v >= 2 && last_use[static_cast<std::size_t>(v)] == k) free_regs.push_back(reg[static_cast<std::size_t>(v)]);
    const int partner = sched.partner[static_cast<std::size_t>(i)];
    if (partner < 0) {
      op.dst = allocate(i + 2);
    } else {
      // sin and cos in one call: the wanted one into dst (and `last`), the other into b
      const int first = sched.wanted[static_cast<std::size_t>(i)];
      const int second = first == i + 2 ? partner + 2 : i + 2;
      const bool sin_first = nodes[static_cast<std::size_t>(first - 2)].code == TapeCode::sin;
      op.code = sin_first ? TapeCode::sincos : TapeCode::cossin;
      op.dst = allocate(first);
      op.b = allocate(second);
    }
    if (n_regs > static_cast<int>(TapeProgram::kMaxRegisters)) return std::nullopt;
    // take the previous result (or the input first read) from a machine
    // register where possible
    const std::uint8_t prev = ops.empty() ? op.a : ops.back().dst;
    const bool commutes = op.code == TapeCode::add || op.code == TapeCode::mul;
    if (commutes && op.a != prev && op.b == prev) std::swap(op.a, op.b);
    op.chained = op.a == prev;
    ops.push_back(op);
  }
  TapeProgram p;
  if (!ops.empty()) {
    p.first_input_ = ops.front().a <= 1 ? ops.front().a : 0;
    ops.front().chained = ops.front().a <= 1;
  }
  // each part: the last result, a register, or a constant
  for (std::size_t i = 0; i < 6; ++i) {
    const int v = outputs[i];
    if (v < 0) {
      p.out_[i] = TapeProgram::kConstant;
    } else if (v >= 2 && !ops.empty() && reg[static_cast<std::size_t>(v)] == ops.back().dst) {
      p.out_[i] = TapeProgram::kLast;
    } else {
      p.out_[i] = reg[static_cast<std::size_t>(v)];
    }
  }
  p.constant_parts_ = constants;
  p.ops_ = std::move(ops);
  return p;
}

}  // namespace rb
