#pragma once
// Field tables: one description per definition type (a vehicle file's
// chassis, axles, tyre, ...) of each Lua field it has: its name, its Lua
// type, its unit and meaning, and where it lives in the C++ struct. Reading
// a file, pushing a definition back to Lua, refusing unknown or mistyped
// fields and the generated Lua reference (tools/luadoc reads docBlocks())
// all walk the same table, so they cannot disagree.
//
//   const FieldTable<SteeringDef> kSteering{"VehicleSteering", "angles and rate", {
//       number("max_angle", &SteeringDef::maxAngle_rad, "rad", "at standstill"),
//       ...}};
//
// Reading throws FieldError with the field's path ("axles[2].suspension:
// unknown field 'frequncy' (did you mean: frequency?) (valid: ...)");
// ranges and consistency stay with the C++ side's validation
// (e.g. vehicle::validateVehicleDef), which C++-made definitions need too.
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "vehicle/curve.h"

struct lua_State;

namespace tumble::script {

struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Lua-stack primitives the field builders use (definition_fields.cpp). The
/// value read is on top of the stack; `path` names it in messages.
namespace fields {
Real readNumber(lua_State* L, const std::string& path, const char* unit);
bool readBool(lua_State* L, const std::string& path);
std::string readString(lua_State* L, const std::string& path);
Vec3 readVec3(lua_State* L, const std::string& path, const char* unit);
std::vector<Real> readNumbers(lua_State* L, const std::string& path);
vehicle::Curve readCurve(lua_State* L, const std::string& path, const char* xUnit, const char* yUnit);
void pushNumber(lua_State* L, double v);
void pushBool(lua_State* L, bool v);
void pushString(lua_State* L, const std::string& v);
void pushVec3(lua_State* L, const Vec3& v);  ///< as the file writes it: {x, y, z}
void pushNumbers(lua_State* L, const std::vector<Real>& v);
void pushCurve(lua_State* L, const vehicle::Curve& c);
/// Calls `each(key)` for each key of the table on top of the stack (raw);
/// throws for a key that is not a string.
void forEachKey(lua_State* L, const std::string& path, const std::function<void(const std::string&)>& each);
/// Pushes t[key] (raw read: no metamethod runs); returns false and pushes
/// nothing when it is nil.
bool getRaw(lua_State* L, const char* key);
void pop(lua_State* L);
/// Pushes a new table / sets t[key] = top (popped).
void newTable(lua_State* L);
void setField(lua_State* L, const char* key);
void setIndex(lua_State* L, int i);
/// Length of the list on top of the stack; throws unless it is a table.
int listLength(lua_State* L, const std::string& path, const char* form);
/// Pushes item i of the list on top of the stack.
void getItem(lua_State* L, int i);
/// Values as the docs show them: 1.5, {0.75, -0.2, 1.3}, "open".
std::string showNumber(double v);
std::string showVec3(const Vec3& v);
std::string showNumbers(const std::vector<Real>& v);
std::string quoted(const std::string& text);
}  // namespace fields

template <class T>
class FieldTable {
 public:
  struct Field {
    const char* name;
    std::string luaType;  ///< as the docs show it: number, boolean, string, number[], VehicleAxle[], ...
    std::string doc;      ///< meaning and unit
    /// Reads the value on top of the stack into the object.
    std::function<void(lua_State*, const std::string& path, T&)> read;
    /// Pushes the object's value; false when the field is left out (an empty mesh path).
    std::function<bool(lua_State*, const T&)> push;
    /// The default as the docs show it, from a default-made object ("" none).
    std::function<std::string(const T&)> show;
  };
  /// Checks the whole object after its fields were read (cross-field rules).
  using Check = std::function<void(const std::string& path, const T&)>;

  FieldTable(std::string docName, std::string docText, std::vector<Field> fields, Check check = nullptr)
      : m_docName(std::move(docName)), m_docText(std::move(docText)), m_fields(std::move(fields)),
        m_check(std::move(check)) {}

  const std::string& docName() const { return m_docName; }
  const std::vector<Field>& fields() const { return m_fields; }

  /// Reads the table on top of the stack (left there) into `out`: fields it
  /// leaves out keep out's values.
  void read(lua_State* L, const std::string& path, T& out) const {
    std::set<std::string> names;
    for (const Field& f : m_fields) names.insert(f.name);
    fields::forEachKey(L, path, [&](const std::string& key) {
      if (!names.count(key)) throw FieldError(prefix(path) + unknownField(key, names));
    });
    for (const Field& f : m_fields) {
      if (!fields::getRaw(L, f.name)) continue;
      f.read(L, join(path, f.name), out);
      fields::pop(L);
    }
    if (m_check) m_check(path, out);
  }
  /// Pushes `value` as a table in the file's format (reads back the same).
  void push(lua_State* L, const T& value) const {
    fields::newTable(L);
    for (const Field& f : m_fields)
      if (f.push(L, value)) fields::setField(L, f.name);
  }
  /// The doc block tools/luadoc turns into the reference (@class with a
  /// @field line per field, each with its default).
  std::string docBlock() const {
    const T defaults{};
    std::ostringstream out;
    out << "/// @class " << m_docName << "\n";
    std::istringstream text(m_docText);
    for (std::string line; std::getline(text, line);) out << "/// " << line << "\n";
    for (const Field& f : m_fields) {
      out << "/// @field " << f.name << "? " << f.luaType << " " << f.doc;
      if (f.show) {
        const std::string d = f.show(defaults);
        if (!d.empty()) out << " (default " << d << ")";
      }
      out << "\n";
    }
    return out.str();
  }

  static std::string join(const std::string& path, const char* name) {
    return path.empty() ? std::string(name) : path + "." + name;
  }

 private:
  static std::string prefix(const std::string& path) { return path.empty() ? std::string() : path + ": "; }
  static std::string unknownField(const std::string& key, const std::set<std::string>& names);

  std::string m_docName, m_docText;
  std::vector<Field> m_fields;
  Check m_check;
};

/// The one wording of an unknown field (internal/lua_util.h's unknownFieldMessage).
std::string unknownFieldText(const std::string& key, const std::set<std::string>& names);

template <class T>
std::string FieldTable<T>::unknownField(const std::string& key, const std::set<std::string>& names) {
  return unknownFieldText(key, names);
}

// ---- builders -----------------------------------------------------------------
// Each makes a Field from a member pointer. `unit` goes into messages and docs.

template <class T>
typename FieldTable<T>::Field number(const char* name, Real T::*m, const char* unit, std::string doc,
                                     std::string defaultText = {}) {
  return {name, "number", std::move(doc) + (*unit ? std::string(", ") + unit : std::string()),
          [m, unit](lua_State* L, const std::string& path, T& o) { o.*m = fields::readNumber(L, path, unit); },
          [m](lua_State* L, const T& o) { return fields::pushNumber(L, o.*m), true; },
          [m, defaultText](const T& o) { return defaultText.empty() ? fields::showNumber(o.*m) : defaultText; }};
}

template <class T>
typename FieldTable<T>::Field boolean(const char* name, bool T::*m, std::string doc) {
  return {name, "boolean", std::move(doc),
          [m](lua_State* L, const std::string& path, T& o) { o.*m = fields::readBool(L, path); },
          [m](lua_State* L, const T& o) { return fields::pushBool(L, o.*m), true; },
          [m](const T& o) { return std::string(o.*m ? "true" : "false"); }};
}

/// A string; `check` refuses bad values (a path leaving the mod); an empty
/// string is left out when pushed back.
template <class T>
typename FieldTable<T>::Field text(const char* name, std::string T::*m, std::string doc,
                                   std::function<void(const std::string& path, const std::string&)> check = nullptr) {
  return {name, "string", std::move(doc),
          [m, check](lua_State* L, const std::string& path, T& o) {
            std::string v = fields::readString(L, path);
            if (check) check(path, v);
            o.*m = std::move(v);
          },
          [m](lua_State* L, const T& o) {
            if ((o.*m).empty()) return false;
            fields::pushString(L, o.*m);
            return true;
          },
          [m](const T& o) { return (o.*m).empty() ? std::string() : fields::quoted(o.*m); }};
}

template <class T>
typename FieldTable<T>::Field vec3(const char* name, Vec3 T::*m, const char* unit, std::string doc) {
  return {name, "number[]", std::move(doc) + ", " + unit,
          [m, unit](lua_State* L, const std::string& path, T& o) { o.*m = fields::readVec3(L, path, unit); },
          [m](lua_State* L, const T& o) { return fields::pushVec3(L, o.*m), true; },
          [m](const T& o) { return fields::showVec3(o.*m); }};
}

template <class T>
typename FieldTable<T>::Field numbers(const char* name, std::vector<Real> T::*m, std::string doc) {
  return {name, "number[]", std::move(doc),
          [m](lua_State* L, const std::string& path, T& o) { o.*m = fields::readNumbers(L, path); },
          [m](lua_State* L, const T& o) { return fields::pushNumbers(L, o.*m), true; },
          [m](const T& o) { return fields::showNumbers(o.*m); }};
}

template <class T>
typename FieldTable<T>::Field curve(const char* name, vehicle::Curve T::*m, const char* xUnit, const char* yUnit,
                                    std::string doc) {
  return {name, "number[][]",
          "{{" + std::string(xUnit) + ", " + yUnit + "}, ...}" + (doc.empty() ? std::string() : " " + doc),
          [m, xUnit, yUnit](lua_State* L, const std::string& path, T& o) {
            o.*m = fields::readCurve(L, path, xUnit, yUnit);
          },
          [m](lua_State* L, const T& o) { return fields::pushCurve(L, o.*m), true; }, nullptr};
}

/// One of a few names, each standing for a C++ value (an enum, or a bool).
template <class T, class V>
typename FieldTable<T>::Field choice(const char* name, V T::*m, std::vector<std::pair<const char*, V>> names,
                                     std::string doc) {
  std::string form;
  for (std::size_t i = 0; i < names.size(); ++i)
    form += (i == 0 ? "\"" : i + 1 == names.size() ? " or \"" : ", \"") + std::string(names[i].first) + "\"";
  return {name, "string", std::move(doc) + ": " + form,
          [m, names, form](lua_State* L, const std::string& path, T& o) {
            const std::string v = fields::readString(L, path);
            for (const auto& [n, value] : names)
              if (v == n) {
                o.*m = value;
                return;
              }
            throw FieldError(path + ": expected " + form + ", got \"" + v + "\"");
          },
          [m, names](lua_State* L, const T& o) {
            for (const auto& [n, value] : names)
              if (o.*m == value) return fields::pushString(L, n), true;
            return false;
          },
          [m, names](const T& o) {
            for (const auto& [n, value] : names)
              if (o.*m == value) return fields::quoted(n);
            return std::string();
          }};
}

/// A sub-table described by its own field table.
template <class T, class C>
typename FieldTable<T>::Field table(const char* name, C T::*m, const FieldTable<C>& sub, std::string doc) {
  return {name, sub.docName(), std::move(doc),
          [m, &sub](lua_State* L, const std::string& path, T& o) { sub.read(L, path, o.*m); },
          [m, &sub](lua_State* L, const T& o) { return sub.push(L, o.*m), true; }, nullptr};
}

/// A list of sub-tables. `seed` makes the starting value of item i from the
/// items read before it (e.g. an axle copies the one before).
template <class T, class C>
typename FieldTable<T>::Field list(const char* name, std::vector<C> T::*m, const FieldTable<C>& sub, std::string doc,
                                   std::function<C(const std::vector<C>& before)> seed) {
  return {name, sub.docName() + "[]", std::move(doc),
          [m, &sub, seed](lua_State* L, const std::string& path, T& o) {
            const int n = fields::listLength(L, path, ("a list of " + sub.docName() + " tables").c_str());
            std::vector<C> items;
            for (int i = 1; i <= n; ++i) {
              fields::getItem(L, i);
              C item = seed(items);
              sub.read(L, path + "[" + std::to_string(i) + "]", item);
              fields::pop(L);
              items.push_back(std::move(item));
            }
            o.*m = std::move(items);
          },
          [m, &sub](lua_State* L, const T& o) {
            fields::newTable(L);
            for (std::size_t i = 0; i < (o.*m).size(); ++i) {
              sub.push(L, (o.*m)[i]);
              fields::setIndex(L, int(i + 1));
            }
            return true;
          },
          nullptr};
}

}  // namespace tumble::script
