#include "vtkCAOSceneExchange.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstdint>
#include <limits>

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
  const double inf = std::numeric_limits<double>::infinity();
  const bool empty = !(this->Local[0] <= this->Local[1]);
  double send[7], common[7];
  for (int d = 0; d < 3; ++d)
  {
    send[d] = empty ? inf : this->Local[2 * d];
    send[3 + d] = empty ? inf : -this->Local[2 * d + 1];
  }
  send[6] = changed ? -1.0 : 0.0;
  if (!controller->AllReduce(send, common, 7, vtkCommunicator::MIN_OP))
    return changed; // (a broken communicator: this process's own view)
  for (int d = 0; d < 3; ++d)
  {
    this->Common[2 * d] = common[d];
    this->Common[2 * d + 1] = -common[3 + d];
  }
  if (!(this->Common[0] <= this->Common[1]))
    this->Common = { { 1, -1, 1, -1, 1, -1 } };
  const bool any = common[6] < 0.0;
  this->ChangeCount += any;
  return any;
}

bool SceneExchange::OrGrid(vtkMultiProcessController* controller, cao::BitGrid& grid)
{
  const std::size_t words = static_cast<std::size_t>(grid.nx) * grid.ny * grid.words;
  if (grid.bits.size() != words)
    grid.bits.assign(words, 0u); // nothing here, or a failed fill: zeros
  std::vector<std::uint32_t> merged(words, 0u);
  static_assert(sizeof(unsigned int) == sizeof(std::uint32_t), "the grid's words are unsigned ints");
  const bool ok = words == 0 ||
    controller->AllReduce(reinterpret_cast<const unsigned int*>(grid.bits.data()),
      reinterpret_cast<unsigned int*>(merged.data()), static_cast<vtkIdType>(words),
      vtkCommunicator::BITWISE_OR_OP);
  if (ok)
    grid.bits.swap(merged);
  return ok;
}

bool SceneExchange::Xor(vtkMultiProcessController* controller, std::vector<std::uint32_t>& words)
{
  std::vector<std::uint32_t> merged(words.size(), 0u);
  const bool ok = words.empty() ||
    controller->AllReduce(reinterpret_cast<const unsigned int*>(words.data()),
      reinterpret_cast<unsigned int*>(merged.data()), static_cast<vtkIdType>(words.size()),
      vtkCommunicator::BITWISE_XOR_OP);
  if (ok)
    words.swap(merged);
  return ok;
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
