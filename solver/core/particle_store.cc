#include "solver/core/particle_store.h"

namespace sph {

namespace {
template <class T, int D>
Column<T>& make(ParticleStore<D>& s, const char* name, bool persistent) {
  return s.template add<T>(name, "core", persistent);
}
}  // namespace

template <int D>
ParticleStore<D>::ParticleStore()
    : x(make<Vec<D>>(*this, "position", true)),
      v(make<Vec<D>>(*this, "velocity", true)),
      a(make<Vec<D>>(*this, "acceleration", true)),
      rho(make<double>(*this, "density", true)),
      p(make<double>(*this, "pressure", true)),
      m(make<double>(*this, "mass", true)),
      kind(make<Kind>(*this, "kind", true)),
      material(make<std::uint16_t>(*this, "material", true)),
      id(make<ParticleId>(*this, "id", true)) {
  a.set_ghost(false);  // only the owner integrates with it
}

template <int D>
void ParticleStore<D>::resize(std::size_t size, std::size_t owned) {
  for (auto& c : columns_) c->resize(size);
  size_ = size;
  owned_ = owned;
}

template <int D>
void ParticleStore<D>::reorder_owned(const std::vector<std::uint32_t>& order) {
  for (auto& c : columns_) c->permute(order);
  size_ = owned_ = order.size();
}

template <int D>
std::map<std::string, std::size_t> ParticleStore<D>::memory_by_owner() const {
  std::map<std::string, std::size_t> out;
  for (const auto& c : columns_) out[c->owner()] += c->capacity_bytes();
  return out;
}

template <int D>
std::size_t ParticleStore<D>::persistent_bytes_per_particle() const {
  std::size_t b = 0;
  for (const auto& c : columns_)
    if (c->persistent()) b += c->elem_bytes();
  return b;
}

template class ParticleStore<2>;
template class ParticleStore<3>;

}  // namespace sph
