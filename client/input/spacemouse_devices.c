/* spacemouse_devices.c — the device table (see SPACEMOUSE-NOTES.md: Devices). */
#include "spacemouse_devices.h"

typedef struct model {
    uint16_t product;
    const char *name;
} model;

static const uint16_t vendors[] = {FC_SM_VENDOR_3DCONNEXION, FC_SM_VENDOR_LOGITECH};

/* Logitech-era SpaceMice: the only 046d products accepted. */
static const model logitech_models[] = {
    {0xc603, "SpaceMouse Plus XT"},    {0xc605, "CADman"},
    {0xc606, "SpaceMouse Classic"},    {0xc621, "Spaceball 5000"},
    {0xc623, "SpaceTraveler"},         {0xc625, "SpacePilot"},
    {0xc626, "SpaceNavigator"},        {0xc627, "SpaceExplorer"},
    {0xc628, "SpaceNavigator for Notebooks"}, {0xc629, "SpacePilot Pro"},
    {0xc62b, "SpaceMouse Pro"},
};

/* Named 256f products, for messages only: acceptance does not depend on this list. */
static const model connexion_models[] = {
    {0xc62e, "SpaceMouse Wireless (cable)"}, {0xc62f, "SpaceMouse Wireless (receiver)"},
    {0xc631, "SpaceMouse Pro Wireless (cable)"}, {0xc632, "SpaceMouse Pro Wireless (receiver)"},
    {0xc633, "SpaceMouse Enterprise"}, {0xc635, "SpaceMouse Compact"},
    {0xc636, "SpaceMouse Module"},     {0xc63a, "SpaceMouse Wireless BT"},
    {0xc652, "Universal Receiver"},
};

/* 256f products without a puck: CadMouse family, keyboards and numpad. */
static const uint16_t connexion_excluded[] = {
    0xc650, 0xc651, 0xc654, 0xc655, 0xc656, 0xc657, 0xc658, 0xc62c, 0xc664, 0xc665, 0xc668,
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

size_t fc_sm_vendor_count(void)
{
    return COUNT(vendors);
}

uint16_t fc_sm_vendor(size_t index)
{
    return index < COUNT(vendors) ? vendors[index] : 0;
}

static const model *find_model(const model *models, size_t n, uint16_t product)
{
    for (size_t i = 0; i < n; i++)
        if (models[i].product == product)
            return &models[i];
    return NULL;
}

static bool connexion_excluded_product(uint16_t product)
{
    for (size_t i = 0; i < COUNT(connexion_excluded); i++)
        if (connexion_excluded[i] == product)
            return true;
    return false;
}

bool fc_sm_device_supported(uint16_t vendor, uint16_t product)
{
    if (vendor == FC_SM_VENDOR_3DCONNEXION)
        return !connexion_excluded_product(product);
    if (vendor == FC_SM_VENDOR_LOGITECH)
        return find_model(logitech_models, COUNT(logitech_models), product) != NULL;
    return false;
}

const char *fc_sm_device_name(uint16_t vendor, uint16_t product)
{
    const model *m = NULL;
    if (vendor == FC_SM_VENDOR_3DCONNEXION)
        m = find_model(connexion_models, COUNT(connexion_models), product);
    else if (vendor == FC_SM_VENDOR_LOGITECH)
        m = find_model(logitech_models, COUNT(logitech_models), product);
    if (m)
        return m->name;
    return vendor == FC_SM_VENDOR_3DCONNEXION ? "3Dconnexion device" : "unknown device";
}
