#include "vtkCAOSceneExchange.h"

#include "caoAORadius.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace
{
/// Bounds as minima and negated maxima (one MIN reduction; an empty box,
/// min > max, as +infinity so that it takes no part).
void Pack(const std::array<double, 6>& b, double* values)
{
  const double inf = std::numeric_limits<double>::infinity();
  const bool empty = !(b[0] <= b[1]);
  for (int d = 0; d < 3; ++d)
  {
    values[d] = empty ? inf : b[2 * d];
    values[3 + d] = empty ? inf : -b[2 * d + 1];
  }
}

/// `words` becomes the reduction of every process's (the same length on each).
bool Words(vtkMultiProcessController* controller, std::vector<std::uint32_t>& words, int operation)
{
  static_assert(sizeof(unsigned int) == sizeof(std::uint32_t), "the grid's words are unsigned ints");
  std::vector<std::uint32_t> merged(words.size(), 0u);
  const bool ok = words.empty() ||
    controller->AllReduce(reinterpret_cast<const unsigned int*>(words.data()),
      reinterpret_cast<unsigned int*>(merged.data()), static_cast<vtkIdType>(words.size()), operation);
  if (ok)
    words.swap(merged);
  return ok;
}

std::array<double, 6> Unpack(const double* values)
{
  std::array<double, 6> b{ { values[0], -values[3], values[1], -values[4], values[2], -values[5] } };
  if (!(b[0] <= b[1]))
    b = { { 1, -1, 1, -1, 1, -1 } };
  return b;
}
}

namespace vtkCAO
{
bool SceneExchange::Frame(vtkMultiProcessController* controller, const std::vector<double>& key,
  const std::function<std::array<double, 6>()>& localBounds)
{
  const bool changed = key != this->Key || this->Key.empty();
  if (changed)
  {
    this->Local = localBounds();
    this->Key = key;
  }
  // One reduction: the minima, the negated maxima, and the negated change.
  double values[7];
  Pack(this->Local, values);
  values[6] = changed ? -1.0 : 0.0;
  if (!Min(controller, values, 7))
    return changed; // (a broken communicator: this process's own view)
  this->Common = Unpack(values);
  const bool any = values[6] < 0.0;
  this->ChangeCount += any;
  return any;
}

bool SceneExchange::CommonBounds(vtkMultiProcessController* controller, std::array<double, 6>& bounds)
{
  double values[6];
  Pack(bounds, values);
  const bool ok = Min(controller, values, 6);
  bounds = Unpack(values);
  return ok;
}

bool SceneExchange::CommonArea(vtkMultiProcessController* controller, const std::vector<cao::MeshView>& pieces,
  const std::vector<int>& pieceActor, int actors, double signature, double& area)
{
  // Every call below is made by every process, in the same order.
  const double n = static_cast<double>(actors);
  double agreed[4] = { n, -n, signature, -signature };
  const bool same = Min(controller, agreed, 4) && agreed[0] == -agreed[1] && agreed[2] == -agreed[3];
  const int groups = same ? actors : 1;
  std::vector<double> mine(static_cast<std::size_t>(groups), 0.0);
  area = 0.0;
  if (groups == 0)
    return true; // (no actor on any process: agreed, nothing to gather)
  for (int a = 0; a < groups; ++a)
  {
    double count = 0.0, sum = 0.0;
    for (std::size_t k = 0; k < pieces.size(); ++k)
      if (!same || pieceActor[k] == a)
      {
        count += static_cast<double>(pieces[k].triangles->size());
        for (double c : *pieces[k].points)
          sum += c;
        mine[static_cast<std::size_t>(a)] += cao::MeshArea(pieces[k]);
      }
    area += mine[static_cast<std::size_t>(a)];
    double share[4] = { count, -count, sum, -sum };
    const bool replicated = same && Min(controller, share, 4) && count > 0.0 && share[0] == -share[1] &&
      share[2] == -share[3];
    if (replicated)
      mine[static_cast<std::size_t>(a)] = -1.0 - mine[static_cast<std::size_t>(a)]; // (marked: counted once)
  }
  std::vector<double> all;
  if (!Gather(controller, mine, all) || all.size() % mine.size() != 0)
    return false;
  double total = 0.0;
  for (int a = 0; a < groups; ++a)
  {
    const double own = mine[static_cast<std::size_t>(a)];
    if (own < 0.0)
      total += -1.0 - own; // replicated: this process's, once
    else
      for (std::size_t p = 0; p < all.size() / mine.size(); ++p)
        total += all[p * mine.size() + static_cast<std::size_t>(a)];
  }
  area = total;
  return true;
}

bool SceneExchange::CombineGrid(vtkMultiProcessController* controller, const std::vector<cao::MeshView>& pieces,
  const std::vector<int>& pieceActor, int actors, double signature, double tolerance, cao::BitGrid& grid,
  std::string& error)
{
  // Every call below is made by every process, in the same order: the
  // loops' counts come from reduced or shared numbers.
  const double n = static_cast<double>(actors);
  double agreed[4] = { n, -n, signature, -signature };
  const bool same = Min(controller, agreed, 4) && agreed[0] == -agreed[1] && agreed[2] == -agreed[3];
  const std::size_t words = static_cast<std::size_t>(grid.nx) * grid.ny * grid.words;
  std::vector<std::uint32_t> mine(words, 0u);
  bool failed = false;
  grid.openEdges.clear();
  for (int a = 0; a < (same ? actors : 1); ++a)
  {
    std::vector<std::uint32_t> parity(words, 0u), surface(words, 0u), shell(words, 0u);
    std::vector<double> edges, pieceEdges, allEdges;
    double count = 0.0, sum = 0.0; // this process's share of the actor, to find it replicated
    for (std::size_t k = 0; k < pieces.size() && !failed; ++k)
      if (!same || pieceActor[k] == a)
      {
        count += static_cast<double>(pieces[k].triangles->size());
        for (double c : *pieces[k].points)
          sum += c;
        failed = !cao::PieceBits(pieces[k], grid, same ? &parity : nullptr, same ? &surface : nullptr, &shell, error);
        if (same && !failed)
        {
          cao::OpenEdges(pieces[k], pieceEdges);
          edges.insert(edges.end(), pieceEdges.begin(), pieceEdges.end());
        }
      }
    bool closed = false;
    if (same)
    {
      double share[4] = { count, -count, sum, -sum };
      const bool replicated = Min(controller, share, 4) && count > 0.0 && share[0] == -share[1] &&
        share[2] == -share[3];
      const bool gathered = Gather(controller, replicated ? std::vector<double>() : edges, allEdges);
      const bool matched =
        gathered && (replicated ? edges.empty() : cao::OpenEdgesOfPieces(allEdges, tolerance) == 0);
      std::vector<std::uint32_t> whole = parity;
      const bool xored = Xor(controller, whole);
      if (replicated)
        whole = parity;
      closed = xored && matched && words > 0 && cao::ParityClosed(grid, whole);
      if (closed)
        for (std::size_t w = 0; w < words; ++w)
          mine[w] |= whole[w] | surface[w];
    }
    if (!closed)
      for (std::size_t w = 0; w < words; ++w)
        mine[w] |= shell[w];
    grid.openEdges.push_back(closed ? 0 : 1);
  }
  if (failed)
    mine.assign(words, 0u); // this process's share: zeros
  grid.bits.swap(mine);
  const bool ored = Words(controller, grid.bits, vtkCommunicator::BITWISE_OR_OP);
  if (!ored)
    error = "the processes' grids could not be combined";
  return !failed && ored;
}

bool SceneExchange::Xor(vtkMultiProcessController* controller, std::vector<std::uint32_t>& words)
{
  return Words(controller, words, vtkCommunicator::BITWISE_XOR_OP);
}

bool SceneExchange::Min(vtkMultiProcessController* controller, double* values, int count)
{
  std::vector<double> common(static_cast<std::size_t>(count));
  const bool ok = controller->AllReduce(values, common.data(), count, vtkCommunicator::MIN_OP) != 0;
  if (ok)
    std::copy(common.begin(), common.end(), values);
  return ok;
}

bool SceneExchange::Gather(vtkMultiProcessController* controller, const std::vector<double>& mine,
  std::vector<double>& all)
{
  const int processes = controller->GetNumberOfProcesses();
  const long long length = static_cast<long long>(mine.size());
  std::vector<long long> lengths(static_cast<std::size_t>(processes), 0);
  if (!controller->AllGather(&length, lengths.data(), 1))
    return false;
  std::vector<vtkIdType> counts(lengths.size()), offsets(lengths.size());
  vtkIdType total = 0;
  for (std::size_t i = 0; i < lengths.size(); ++i)
  {
    counts[i] = static_cast<vtkIdType>(lengths[i]);
    offsets[i] = total;
    total += counts[i];
  }
  std::vector<double> send = mine; // (the buffers are never empty)
  send.push_back(0.0);
  all.assign(static_cast<std::size_t>(total) + 1, 0.0);
  const bool ok = controller->AllGatherV(send.data(), all.data(), static_cast<vtkIdType>(mine.size()),
                    counts.data(), offsets.data()) != 0;
  all.resize(static_cast<std::size_t>(total));
  return ok;
}
}
