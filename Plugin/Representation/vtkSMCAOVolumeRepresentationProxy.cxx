#include "vtkSMCAOVolumeRepresentationProxy.h"

#include "vtkCAOFrameReportInformation.h"
#include "vtkClientServerStream.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVSession.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMProxyManager.h"
#include "vtkSMProxyProperty.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMStringVectorProperty.h"
#include "vtkStringList.h"

#include <algorithm>
#include <cstring>
#include <set>

vtkStandardNewMacro(vtkSMCAOVolumeRepresentationProxy);

namespace
{
/// The clip meshes' consumer in place of the representation (see the
/// class comment): an internal proxy, in no pipeline group, that passes a
/// mesh's changes on to its owner.
class vtkSMCAOClipMeshRelay : public vtkSMProxy
{
public:
  static vtkSMCAOClipMeshRelay* New();
  vtkTypeMacro(vtkSMCAOClipMeshRelay, vtkSMProxy);
  vtkWeakPointer<vtkSMCAOVolumeRepresentationProxy> Owner;
  /// ParaView updates a changed property's consumers (File > Change File
  /// swaps a reader in Clip Meshes, then updates its consumer): the owner's.
  void UpdateVTKObjects() override
  {
    if (this->Owner)
      this->Owner->UpdateVTKObjects();
  }

protected:
  vtkSMCAOClipMeshRelay()
  {
    // (ParaView compares a consumer's group with its own when it deletes a source)
    // (its definition in ContextualAORepresentation.xml, which Python looks up)
    this->SetXMLGroup("contextual_ao_internal");
    this->SetXMLName("ClipMeshRelay");
    this->SetXMLLabel("Clip Mesh Relay");
  }
  void MarkDirtyFromProducer(vtkSMProxy* modifiedProxy, vtkSMProxy* producer, vtkSMProperty* property) override
  {
    if (this->Owner)
      this->Owner->ClipMeshModified(modifiedProxy, producer, property);
  }
};
vtkStandardNewMacro(vtkSMCAOClipMeshRelay);

/// A producer's consumer links (protected in vtkSMProxy, where the proxy
/// properties make them), named through a subclass that is never made.
struct ConsumerLinks : vtkSMProxy
{
  static void Add(vtkSMProxy* producer, vtkSMProperty* property, vtkSMProxy* consumer)
  {
    (producer->*(&ConsumerLinks::AddConsumer))(property, consumer);
  }
  static void Remove(vtkSMProxy* producer, vtkSMProperty* property, vtkSMProxy* consumer)
  {
    (producer->*(&ConsumerLinks::RemoveConsumer))(property, consumer);
  }
};
}

namespace
{
/// Every live proxy of the class (server-manager proxies are made and used
/// on the application's main thread). Never destroyed: a proxy released
/// during the exit's static destruction still finds it.
std::vector<vtkSMCAOVolumeRepresentationProxy*>& Instances()
{
  static auto* instances = new std::vector<vtkSMCAOVolumeRepresentationProxy*>();
  return *instances;
}
}

vtkSMCAOVolumeRepresentationProxy::vtkSMCAOVolumeRepresentationProxy()
{
  Instances().push_back(this);
}

vtkSMCAOVolumeRepresentationProxy::~vtkSMCAOVolumeRepresentationProxy()
{
  auto& all = Instances();
  all.erase(std::remove(all.begin(), all.end(), this), all.end());
  if (this->Watched)
    this->Watched->RemoveObserver(this->Observer);
  if (this->WatchedManager)
    this->WatchedManager->RemoveObserver(this->ManagerObserver);
  vtkSMProperty* meshes = this->GetProperty("ClipMeshes");
  for (const auto& mesh : this->RelayedMeshes)
    if (mesh && meshes)
      ConsumerLinks::Remove(mesh, meshes, this->ClipMeshRelay);
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::ClipMeshModified(
  vtkSMProxy* modifiedProxy, vtkSMProxy* producer, vtkSMProperty* property)
{
  this->MarkDirtyFromProducer(modifiedProxy, producer, property);
}

void vtkSMCAOVolumeRepresentationProxy::SetPropertyModifiedFlag(const char* name, int flag)
{
  this->Superclass::SetPropertyModifiedFlag(name, flag);
  if (name && std::strcmp(name, "ClipMeshes") == 0)
    this->RelinkClipMeshes();
}

void vtkSMCAOVolumeRepresentationProxy::RelinkClipMeshes()
{
  auto* meshes = vtkSMProxyProperty::SafeDownCast(this->GetProperty("ClipMeshes"));
  if (!meshes)
    return;
  if (!this->ClipMeshRelay)
  {
    auto relay = vtkSmartPointer<vtkSMCAOClipMeshRelay>::New();
    relay->Owner = this;
    // (Python asks a consumer for its session's proxy manager when it saves
    // a state; the relay is registered in none of its groups)
    relay->SetSession(this->GetSession());
    this->ClipMeshRelay = relay;
  }
  // The property linked each new mesh to this proxy as its consumer.
  std::vector<vtkWeakPointer<vtkSMProxy>> now;
  for (unsigned int i = 0; i < meshes->GetNumberOfProxies(); ++i)
    if (vtkSMProxy* mesh = meshes->GetProxy(i))
    {
      ConsumerLinks::Remove(mesh, meshes, this);
      ConsumerLinks::Add(mesh, meshes, this->ClipMeshRelay);
      now.emplace_back(mesh);
    }
  for (const auto& mesh : this->RelayedMeshes)
    if (mesh && std::find(now.begin(), now.end(), mesh) == now.end())
      ConsumerLinks::Remove(mesh, meshes, this->ClipMeshRelay);
  this->RelayedMeshes = now;
}

void vtkSMCAOVolumeRepresentationProxy::ProxyUnRegistered(vtkObject*, unsigned long, void* callData)
{
  const auto* info = static_cast<vtkSMProxyManager::RegisteredProxyInformation*>(callData);
  auto* meshes = vtkSMProxyProperty::SafeDownCast(this->GetProperty("ClipMeshes"));
  if (!info || info->Type != vtkSMProxyManager::RegisteredProxyInformation::PROXY || !info->Proxy ||
    !info->GroupName || std::strcmp(info->GroupName, "sources") != 0 || !meshes || !this->WatchedManager)
    return;
  std::vector<unsigned int> listed; // (a mesh may be listed more than once)
  for (unsigned int i = 0; i < meshes->GetNumberOfProxies(); ++i)
    if (meshes->GetProxy(i) == info->Proxy)
      listed.push_back(i);
  if (listed.empty())
    return;
  // Still in the pipeline under another name (a rename registers the new
  // name, then unregisters the old).
  vtkNew<vtkStringList> names;
  this->WatchedManager->GetProxyNames("sources", info->Proxy, names);
  for (int i = 0; i < names->GetNumberOfStrings(); ++i)
    if (!info->ProxyName || std::strcmp(names->GetString(i), info->ProxyName) != 0)
      return;
  for (std::size_t i = 0; i < listed.size(); ++i)
    meshes->RemoveProxy(info->Proxy); // (the first left each time)
  if (auto* modes = vtkSMIntVectorProperty::SafeDownCast(this->GetProperty("ClipMeshModes")))
  {
    std::vector<int> values(modes->GetElements(), modes->GetElements() + modes->GetNumberOfElements());
    for (auto i = listed.rbegin(); i != listed.rend(); ++i)
      if (*i < values.size())
        values.erase(values.begin() + *i);
    if (values.size() != modes->GetNumberOfElements())
    {
      modes->SetNumberOfElements(static_cast<unsigned int>(values.size()));
      if (!values.empty())
        modes->SetElements(values.data());
    }
  }
  this->UpdateVTKObjects();
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::PushPointerHeld(bool held)
{
  vtkSMSession* session = this->GetSession();
  if (!this->ObjectsCreated || !(this->GetLocation() & vtkPVSession::RENDER_SERVER) || !session ||
    !session->GetIsAlive())
    return;
  vtkClientServerStream stream;
  stream << vtkClientServerStream::Invoke << VTKOBJECT(this) << "SetPointerHeld" << (held ? 1 : 0)
         << vtkClientServerStream::End;
  this->ExecuteStream(stream, false, vtkPVSession::RENDER_SERVER);
}

//------------------------------------------------------------------------------
std::vector<vtkSMCAOVolumeRepresentationProxy*>
vtkSMCAOVolumeRepresentationProxy::ShownInRemoteSessions()
{
  std::vector<vtkSMCAOVolumeRepresentationProxy*> found;
  std::set<vtkSMSession*> sessions;
  for (vtkSMCAOVolumeRepresentationProxy* proxy : Instances())
  {
    vtkSMSession* session = proxy->GetSession();
    vtkSMProxy* parent = proxy->GetParentProxy();
    if (!proxy->ObjectsCreated || !session || !session->IsA("vtkSMSessionClient") ||
      sessions.count(session) || !parent || !parent->GetProperty("Representation"))
      continue;
    const char* type = vtkSMPropertyHelper(parent, "Representation").GetAsString();
    if (type && std::strcmp(type, TypeName()) == 0)
    {
      sessions.insert(session);
      found.push_back(proxy);
    }
  }
  return found;
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::UpdatePropertyInformationInternal(vtkSMProperty* property)
{
  this->Superclass::UpdatePropertyInformationInternal(property);
  auto* report = vtkSMStringVectorProperty::SafeDownCast(this->GetProperty("FrameReport"));
  if (!report || (property && property != report) || !this->ObjectsCreated ||
    !this->GetSession() || !this->GetSession()->IsA("vtkSMSessionClient"))
    return;
  vtkNew<vtkCAOFrameReportInformation> information;
  this->GatherInformation(information, vtkPVSession::RENDER_SERVER);
  report->SetElement(0, information->GetReport());
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::CreateVTKObjects()
{
  if (this->ObjectsCreated)
    return;
  this->Superclass::CreateVTKObjects();
  vtkSMProxy* parent = this->GetParentProxy();
  vtkSMProperty* representation = parent ? parent->GetProperty("Representation") : nullptr;
  if (representation && !this->Watched)
  {
    this->Watched = representation;
    this->Observer = representation->AddObserver(
      vtkCommand::ModifiedEvent, this, &vtkSMCAOVolumeRepresentationProxy::RepresentationChanged);
  }
  vtkSMSessionProxyManager* manager = this->GetSessionProxyManager();
  if (manager && !this->WatchedManager)
  {
    this->WatchedManager = manager;
    this->ManagerObserver = manager->AddObserver(
      vtkCommand::UnRegisterEvent, this, &vtkSMCAOVolumeRepresentationProxy::ProxyUnRegistered);
  }
  this->RelinkClipMeshes();
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::RepresentationChanged()
{
  auto* parent = vtkSMPVRepresentationProxy::SafeDownCast(this->GetParentProxy());
  if (this->Choosing || !parent || !this->Watched)
    return;
  const char* type = vtkSMPropertyHelper(this->Watched).GetAsString();
  if (!type || std::strcmp(type, TypeName()) != 0 || parent->GetUsingScalarColoring())
    return;
  vtkSMProperty* colorArray = parent->GetProperty("ColorArrayName");
  auto* arrays = colorArray ? colorArray->FindDomain<vtkSMArrayListDomain>() : nullptr;
  if (!arrays || arrays->GetNumberOfStrings() == 0)
    return; // nothing to colour by: the representation says so when it draws
  // A point array with one component (the mapper draws one), else any point
  // array, else the first. The components are the input's: the represented
  // data is still the previous representation's (an outline has no arrays)
  // until the new type is pushed.
  vtkSMPropertyHelper input(parent, "Input", /*quiet=*/true);
  auto* source = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
  vtkPVDataInformation* data =
    source ? source->GetDataInformation(input.GetOutputPort()) : nullptr;
  auto components = [&](unsigned int i) {
    vtkPVArrayInformation* info =
      data ? data->GetArrayInformation(arrays->GetString(i), arrays->GetFieldAssociation(i)) : nullptr;
    return info ? info->GetNumberOfComponents() : 0;
  };
  const unsigned int count = arrays->GetNumberOfStrings();
  unsigned int index = count;
  for (unsigned int i = 0; i < count && index == count; ++i)
    if (arrays->GetFieldAssociation(i) == vtkDataObject::FIELD_ASSOCIATION_POINTS && components(i) == 1)
      index = i;
  for (unsigned int i = 0; i < count && index == count; ++i)
    if (arrays->GetFieldAssociation(i) == vtkDataObject::FIELD_ASSOCIATION_POINTS)
      index = i;
  if (index == count)
    index = 0;
  this->Choosing = true;
  if (parent->SetScalarColoring(arrays->GetString(index), arrays->GetFieldAssociation(index)))
    parent->RescaleTransferFunctionToDataRange(false, false);
  this->Choosing = false;
}

//------------------------------------------------------------------------------
void vtkSMCAOVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Watching: " << (this->Watched ? "the parent's Representation" : "nothing")
     << "\n";
}
