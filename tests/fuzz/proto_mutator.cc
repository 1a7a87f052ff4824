#include "tests/fuzz/proto_mutator.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sph::fuzz {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

template <typename T>
T pick(std::mt19937_64& rng, const std::vector<T>& values) {
  return values[std::uniform_int_distribution<std::size_t>(0, values.size() - 1)(rng)];
}

bool coin(std::mt19937_64& rng, int one_in) {
  return std::uniform_int_distribution<int>(0, one_in - 1)(rng) == 0;
}

double edge_double(std::mt19937_64& rng, double now) {
  const double inf = std::numeric_limits<double>::infinity();
  return pick<double>(rng, {0.0,
                            -0.0,
                            1.0,
                            -1.0,
                            0.5,
                            2.0,
                            1e-300,
                            -1e300,
                            1e300,
                            1e-12,
                            1e12,
                            std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::denorm_min(),
                            inf,
                            -inf,
                            std::numeric_limits<double>::quiet_NaN(),
                            now * 2,
                            now / 2,
                            -now,
                            std::uniform_real_distribution<double>(-10, 10)(rng)});
}

std::int64_t edge_int(std::mt19937_64& rng, std::int64_t now, std::int64_t lo, std::int64_t hi) {
  // Neighbours of the value now wrap around as the field's type would (unsigned arithmetic:
  // no overflow in the mutator itself).
  const auto u = static_cast<std::uint64_t>(now);
  const auto wrap = [](std::uint64_t v) { return static_cast<std::int64_t>(v); };
  return pick<std::int64_t>(
      rng, {0, 1, -1, 2, 3, 100, 1 << 20, lo, hi, lo + 1, hi - 1, wrap(u + 1), wrap(u - 1),
            wrap(u * 2), std::uniform_int_distribution<std::int64_t>(-1000, 1000)(rng)});
}

std::string edge_string(std::mt19937_64& rng, const std::string& now) {
  switch (std::uniform_int_distribution<int>(0, 6)(rng)) {
    case 0:
      return "";
    case 1:
      return now + now;
    case 2:
      return now.substr(0, now.size() / 2);
    case 3:
      return std::string(std::uniform_int_distribution<std::size_t>(1, 5000)(rng), 'a');
    case 4:
      return "../../etc/passwd";
    case 5:
      return "job-1";
    default:
      return now + "\xc3\xa9\x00x";
  }
}

void set_scalar(Message& m, const FieldDescriptor* f, int index, std::mt19937_64& rng) {
  const Reflection* r = m.GetReflection();
  const bool rep = f->is_repeated();
  switch (f->cpp_type()) {
    case FieldDescriptor::CPPTYPE_DOUBLE: {
      const double v =
          edge_double(rng, rep ? r->GetRepeatedDouble(m, f, index) : r->GetDouble(m, f));
      rep ? r->SetRepeatedDouble(&m, f, index, v) : r->SetDouble(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_FLOAT: {
      const auto v = static_cast<float>(edge_double(
          rng, static_cast<double>(rep ? r->GetRepeatedFloat(m, f, index) : r->GetFloat(m, f))));
      rep ? r->SetRepeatedFloat(&m, f, index, v) : r->SetFloat(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_INT32: {
      const auto v = static_cast<std::int32_t>(edge_int(
          rng, rep ? r->GetRepeatedInt32(m, f, index) : r->GetInt32(m, f),
          std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()));
      rep ? r->SetRepeatedInt32(&m, f, index, v) : r->SetInt32(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_INT64: {
      const auto v = edge_int(rng, rep ? r->GetRepeatedInt64(m, f, index) : r->GetInt64(m, f),
                              std::numeric_limits<std::int64_t>::min(),
                              std::numeric_limits<std::int64_t>::max());
      rep ? r->SetRepeatedInt64(&m, f, index, v) : r->SetInt64(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_UINT32: {
      const auto v = static_cast<std::uint32_t>(
          edge_int(rng, rep ? r->GetRepeatedUInt32(m, f, index) : r->GetUInt32(m, f), 0,
                   std::numeric_limits<std::uint32_t>::max()));
      rep ? r->SetRepeatedUInt32(&m, f, index, v) : r->SetUInt32(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_UINT64: {
      const auto v = static_cast<std::uint64_t>(edge_int(
          rng,
          static_cast<std::int64_t>(rep ? r->GetRepeatedUInt64(m, f, index) : r->GetUInt64(m, f)),
          0, std::numeric_limits<std::int64_t>::max()));
      rep ? r->SetRepeatedUInt64(&m, f, index, v) : r->SetUInt64(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_BOOL: {
      const bool v = !(rep ? r->GetRepeatedBool(m, f, index) : r->GetBool(m, f));
      rep ? r->SetRepeatedBool(&m, f, index, v) : r->SetBool(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_ENUM: {
      // Open (proto3) enums hold any number; a valid one most of the time.
      const auto* e = f->enum_type();
      const int v = coin(rng, 4)
                        ? static_cast<int>(edge_int(rng, 0, -1, 1000))
                        : e->value(std::uniform_int_distribution<int>(0, e->value_count() - 1)(rng))
                              ->number();
      rep ? r->SetRepeatedEnumValue(&m, f, index, v) : r->SetEnumValue(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_STRING: {
      std::string v =
          edge_string(rng, rep ? r->GetRepeatedString(m, f, index) : r->GetString(m, f));
      // A proto3 string must stay UTF-8 for the message to serialise; bytes fields take any.
      if (f->type() == FieldDescriptor::TYPE_STRING)
        for (char& ch : v)
          if (static_cast<unsigned char>(ch) >= 0x80 || ch == '\0') ch = 'u';
      rep ? r->SetRepeatedString(&m, f, index, v) : r->SetString(&m, f, v);
      break;
    }
    case FieldDescriptor::CPPTYPE_MESSAGE:
      break;
  }
}

void mutate_field(Message& m, const FieldDescriptor* f, std::mt19937_64& rng, int depth);

// Deeper than any case the parser accepts: stop descending.
constexpr int kMaxDepth = 200;

void mutate_at(Message& m, std::mt19937_64& rng, int depth) {
  const auto* d = m.GetDescriptor();
  if (d->field_count() == 0 || depth > kMaxDepth) return;
  const Reflection* r = m.GetReflection();
  // Descend most of the time into a field that is set, so deep parts of a case change too.
  std::vector<const FieldDescriptor*> set;
  r->ListFields(m, &set);
  const FieldDescriptor* f =
      !set.empty() && !coin(rng, 3)
          ? set[std::uniform_int_distribution<std::size_t>(0, set.size() - 1)(rng)]
          : d->field(std::uniform_int_distribution<int>(0, d->field_count() - 1)(rng));
  mutate_field(m, f, rng, depth);
}

void mutate_field(Message& m, const FieldDescriptor* f, std::mt19937_64& rng, int depth) {
  const Reflection* r = m.GetReflection();
  const bool is_message = f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE;
  if (f->is_repeated()) {
    const int n = r->FieldSize(m, f);
    const int action = std::uniform_int_distribution<int>(0, 3)(rng);
    if (n > 0 && action == 0) {  // remove one
      r->SwapElements(&m, f, std::uniform_int_distribution<int>(0, n - 1)(rng), n - 1);
      r->RemoveLast(&m, f);
    } else if (n == 0 || action == 1) {  // add one: a copy of an element, or a fresh one
      const int from = n > 0 ? std::uniform_int_distribution<int>(0, n - 1)(rng) : -1;
      if (is_message) {
        Message* added = r->AddMessage(&m, f);
        if (from >= 0) added->CopyFrom(r->GetRepeatedMessage(m, f, from));
      } else {
        switch (f->cpp_type()) {
          case FieldDescriptor::CPPTYPE_DOUBLE:
            r->AddDouble(&m, f, from >= 0 ? r->GetRepeatedDouble(m, f, from) : 0);
            break;
          case FieldDescriptor::CPPTYPE_FLOAT:
            r->AddFloat(&m, f, 0);
            break;
          case FieldDescriptor::CPPTYPE_INT32:
            r->AddInt32(&m, f, 0);
            break;
          case FieldDescriptor::CPPTYPE_INT64:
            r->AddInt64(&m, f, 0);
            break;
          case FieldDescriptor::CPPTYPE_UINT32:
            r->AddUInt32(&m, f, 0);
            break;
          case FieldDescriptor::CPPTYPE_UINT64:
            r->AddUInt64(&m, f, 0);
            break;
          case FieldDescriptor::CPPTYPE_BOOL:
            r->AddBool(&m, f, false);
            break;
          case FieldDescriptor::CPPTYPE_ENUM:
            r->AddEnumValue(&m, f, 0);
            break;
          case FieldDescriptor::CPPTYPE_STRING:
            r->AddString(&m, f, from >= 0 ? r->GetRepeatedString(m, f, from) : "");
            break;
          case FieldDescriptor::CPPTYPE_MESSAGE:
            break;
        }
      }
    } else {  // change one
      const int i = std::uniform_int_distribution<int>(0, n - 1)(rng);
      if (is_message)
        mutate_at(*r->MutableRepeatedMessage(&m, f, i), rng, depth + 1);
      else
        set_scalar(m, f, i, rng);
    }
    return;
  }
  if (is_message) {
    if (r->HasField(m, f) && coin(rng, 5))
      r->ClearField(&m, f);
    else
      mutate_at(*r->MutableMessage(&m, f), rng, depth + 1);
    return;
  }
  set_scalar(m, f, -1, rng);
}

}  // namespace

void mutate_message(Message& m, std::mt19937_64& rng) {
  mutate_at(m, rng, 0);
}

}  // namespace sph::fuzz
