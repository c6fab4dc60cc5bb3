#include "vb/dataset/episode_record.h"

#include "vb/engine/error.h"

namespace vb::dataset {

size_t Column::RowSize() const {
  size_t n = 1;
  for (size_t d : row_shape) n *= d;
  return n;
}

size_t Column::Rows() const {
  size_t stored = 0;
  switch (type) {
    case ColumnType::kFloat32: stored = f32.size(); break;
    case ColumnType::kFloat64: stored = f64.size(); break;
    case ColumnType::kInt8:
    case ColumnType::kBool: stored = i8.size(); break;
    case ColumnType::kInt32: stored = i32.size(); break;
  }
  const size_t row = RowSize();
  return row == 0 ? 0 : stored / row;
}

Column& EpisodeRecord::Add(const std::string& path, ColumnType type, std::vector<size_t> row_shape,
                           bool compress) {
  VB_DEMAND(Find(path) == nullptr);
  Column c;
  c.path = path;
  c.type = type;
  c.row_shape = std::move(row_shape);
  c.compress = compress;
  columns.push_back(std::move(c));
  return columns.back();
}

Column* EpisodeRecord::Find(const std::string& path) {
  for (Column& c : columns) {
    if (c.path == path) return &c;
  }
  return nullptr;
}

const Column* EpisodeRecord::Find(const std::string& path) const {
  for (const Column& c : columns) {
    if (c.path == path) return &c;
  }
  return nullptr;
}

void EpisodeRecord::SetText(const std::string& name, const std::string& value) {
  Attribute a;
  a.name = name;
  a.kind = Attribute::Kind::kText;
  a.text = value;
  attributes.push_back(std::move(a));
}

void EpisodeRecord::SetInt(const std::string& name, int64_t value) {
  Attribute a;
  a.name = name;
  a.kind = Attribute::Kind::kInt;
  a.integer = value;
  attributes.push_back(std::move(a));
}

void EpisodeRecord::SetReal(const std::string& name, double value) {
  Attribute a;
  a.name = name;
  a.kind = Attribute::Kind::kReal;
  a.real = value;
  attributes.push_back(std::move(a));
}

const Attribute* EpisodeRecord::FindAttribute(const std::string& name) const {
  for (const Attribute& a : attributes) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

}  // namespace vb::dataset
