// A minimal archetype-table ECS, written only to compare storage layouts in
// lantern-bench-ecs (docs/ecs.md). Entities with the same component set share a table
// whose columns are contiguous arrays; adding or removing a component moves the entity's
// row to another table. Trivially copyable components only; no views, no safety nets.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace lantern::bench {

class ArchetypeWorld {
  public:
    using Mask = std::uint64_t;
    struct Entity {
        std::uint32_t index, generation;
    };

    template <typename T>
    static int type_index() {
        static const int id = next_type_++;
        return id;
    }

    template <typename... T>
    Entity create(const T&... values) {
        Mask mask = ((Mask(1) << type_index<T>()) | ... | 0);
        Table& table = table_for(mask);
        Entity e = new_entity();
        std::uint32_t row = table.append(e.index);
        (std::memcpy(table.column(type_index<T>()) + row * sizeof(T), &values, sizeof(T)), ...);
        records_[e.index] = {&table, row};
        return e;
    }

    template <typename T>
    void add(Entity e, const T& value) {
        Record& r = records_[e.index];
        Table& dst = table_for(r.table->mask | (Mask(1) << type_index<T>()));
        std::uint32_t row = move_row(r, dst);
        std::memcpy(dst.column(type_index<T>()) + row * sizeof(T), &value, sizeof(T));
    }

    template <typename T>
    void remove(Entity e) {
        Record& r = records_[e.index];
        move_row(r, table_for(r.table->mask & ~(Mask(1) << type_index<T>())));
    }

    template <typename T>
    T* get(Entity e) {
        if (generations_[e.index] != e.generation) return nullptr;
        const Record& r = records_[e.index];
        std::byte* col = r.table->column(type_index<T>());
        return col ? reinterpret_cast<T*>(col) + r.row : nullptr;
    }

    template <typename... T, typename F>
    void each(F&& f) {
        Mask need = ((Mask(1) << type_index<T>()) | ...);
        for (auto& [mask, table] : tables_) {
            if ((mask & need) != need) continue;
            std::tuple<T*...> cols{reinterpret_cast<T*>(table->column(type_index<T>()))...};
            for (std::uint32_t i = 0; i < table->entities.size(); ++i) f(std::get<T*>(cols)[i]...);
        }
    }

    void destroy(Entity e) {
        Record& r = records_[e.index];
        r.table->swap_remove(r.row, records_);
        ++generations_[e.index];
        free_.push_back(e.index);
    }

  private:
    struct Table;
    struct Record {
        Table* table = nullptr;
        std::uint32_t row = 0;
    };
    struct Table {
        Mask mask = 0;
        std::vector<std::uint32_t> entities;
        std::array<std::vector<std::byte>, 64> columns; // by type index; empty when absent
        std::array<std::uint32_t, 64> sizes{};
        std::byte* column(int type) { return sizes[type] ? columns[type].data() : nullptr; }
        std::uint32_t append(std::uint32_t entity) {
            entities.push_back(entity);
            for (int t = 0; t < 64; ++t)
                if (sizes[t]) columns[t].resize(entities.size() * sizes[t]);
            return std::uint32_t(entities.size() - 1);
        }
        void swap_remove(std::uint32_t row, std::vector<Record>& records) {
            std::uint32_t last = std::uint32_t(entities.size() - 1);
            if (row != last) {
                for (int t = 0; t < 64; ++t)
                    if (sizes[t]) std::memcpy(&columns[t][row * sizes[t]], &columns[t][last * sizes[t]], sizes[t]);
                entities[row] = entities[last];
                records[entities[row]].row = row;
            }
            entities.pop_back();
            for (int t = 0; t < 64; ++t)
                if (sizes[t]) columns[t].resize(entities.size() * sizes[t]);
        }
    };

    Entity new_entity() {
        if (!free_.empty()) {
            std::uint32_t i = free_.back();
            free_.pop_back();
            return {i, generations_[i]};
        }
        generations_.push_back(0);
        records_.emplace_back();
        return {std::uint32_t(generations_.size() - 1), 0};
    }

    Table& table_for(Mask mask) {
        auto& t = tables_[mask];
        if (!t) {
            t = std::make_unique<Table>();
            t->mask = mask;
            for (int i = 0; i < 64; ++i)
                if (mask & (Mask(1) << i)) t->sizes[i] = type_sizes_[i];
        }
        return *t;
    }

    std::uint32_t move_row(Record& r, Table& dst) {
        Table& src = *r.table;
        std::uint32_t entity = src.entities[r.row];
        std::uint32_t row = dst.append(entity);
        for (int t = 0; t < 64; ++t)
            if (src.sizes[t] && dst.sizes[t])
                std::memcpy(&dst.columns[t][row * dst.sizes[t]], &src.columns[t][r.row * src.sizes[t]], src.sizes[t]);
        src.swap_remove(r.row, records_);
        r = {&dst, row};
        return row;
    }

  public:
    template <typename T>
    void register_type() {
        static_assert(std::is_trivially_copyable_v<T>);
        type_sizes_[type_index<T>()] = sizeof(T);
    }

  private:
    static inline int next_type_ = 0;
    std::array<std::uint32_t, 64> type_sizes_{};
    std::unordered_map<Mask, std::unique_ptr<Table>> tables_;
    std::vector<Record> records_;
    std::vector<std::uint32_t> generations_;
    std::vector<std::uint32_t> free_;
};

} // namespace lantern::bench
